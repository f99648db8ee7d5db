#include "rlrun/tune/worker_liveness.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>

#include "rlrun/core/checked_file.hpp"

namespace rlrun::tune {
namespace {

std::string host_name() {
  char name[256] = {0};
  ::gethostname(name, sizeof name - 1);
  return name;
}

// Field 22 of /proc/<pid>/stat (starttime, in clock ticks since boot); "" when there is no
// such process. The command name (field 2) may hold spaces and parentheses: count from its end.
std::string process_start_time(long pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t close = text.rfind(')');
  if (close == std::string::npos) return "";
  std::istringstream rest(text.substr(close + 2));
  std::string field;
  for (int i = 3; i <= 22 && (rest >> field); ++i)
    if (i == 22) return field;
  return "";
}

std::string heartbeat_path(const std::string& journal, const std::string& worker_id) {
  return journal + ".workers/" + worker_id;
}

double seconds_since_modified(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return 1e30;  // a link's own time: never followed
  const double now =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  return now -
         (static_cast<double>(st.st_mtim.tv_sec) + 1e-9 * static_cast<double>(st.st_mtim.tv_nsec));
}

}  // namespace

nlohmann::json this_worker(const std::string& worker_id) {
  const long pid = static_cast<long>(::getpid());
  return {
      {"id", worker_id}, {"host", host_name()}, {"pid", pid}, {"start", process_start_time(pid)}};
}

bool worker_alive(const nlohmann::json& record, const std::string& journal) {
  if (!record.is_object()) return true;  // not an rlrun worker's trial: cannot tell, leave it
  const auto host = record.find("host");
  const auto pid = record.find("pid");
  const auto start = record.find("start");
  const auto id = record.find("id");
  if (host != record.end() && host->is_string() && *host == host_name() && pid != record.end() &&
      pid->is_number_integer() && start != record.end() && start->is_string()) {
    const std::string now_start = process_start_time(pid->get<long>());
    return !now_start.empty() && now_start == start->get<std::string>();
  }
  if (id == record.end() || !id->is_string()) return true;
  const std::string name = id->get<std::string>();
  if (name.find('/') != std::string::npos || name.empty() || name[0] == '.') return true;
  return seconds_since_modified(heartbeat_path(journal, name)) < kHeartbeatTimeout;
}

Heartbeat::Heartbeat(const std::string& journal, const std::string& worker_id) : name_(worker_id) {
  // <journal>.workers/ beside the journal, not a link to elsewhere, and the heartbeat a regular
  // file in it (core/dir_handle.hpp): a study may come from anyone.
  const auto [dir, journal_name] = DirHandle::open_parent(journal);
  dir_ = dir.make_subdir(journal_name + ".workers");
  dir_.open_for_writing(name_, CheckedFile::Mode::kTruncate);  // fails here, not in the thread
  thread_ = std::thread([this] {
    while (!stop_) {
      try {
        CheckedFile beat = dir_.open_for_writing(name_, CheckedFile::Mode::kTruncate);
        beat << "rlrun tune worker\n";
        beat.close();
      } catch (const std::exception&) {
        // A beat that cannot be written makes this worker look gone later; the study goes on.
      }
      for (int i = 0; i < static_cast<int>(kHeartbeatInterval * 10) && !stop_; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
}

Heartbeat::~Heartbeat() {
  stop_ = true;
  thread_.join();
  dir_.remove(name_);
}

}  // namespace rlrun::tune
