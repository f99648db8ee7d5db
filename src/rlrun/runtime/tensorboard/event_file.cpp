#include "rlrun/runtime/tensorboard/event_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <filesystem>

#include "rlrun/core/crc32c.hpp"
#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace fs = std::filesystem;

namespace {

void put_le(std::string& out, uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>(value >> (8 * i)));
}

// The host name as file names may hold it (TensorBoard only needs "tfevents" in the name).
std::string host_name() {
  char buffer[256] = {};
  if (gethostname(buffer, sizeof buffer - 1) != 0 || buffer[0] == '\0') return "localhost";
  std::string host(buffer);
  for (char& c : host)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '-';
  return host;
}

// Creates `path` only if it does not exist yet (never another run's file).
bool create_exclusively(const std::string& path) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    if (errno == EEXIST) return false;
    throw RuntimeFailure("cannot create " + path + ": " + describe_errno(errno));
  }
  close(fd);
  return true;
}

}  // namespace

std::string tfrecord(const std::string& data) {
  std::string length;
  put_le(length, data.size(), 8);
  std::string record = length;
  put_le(record, masked_crc32c(length), 4);
  record += data;
  put_le(record, masked_crc32c(data), 4);
  return record;
}

EventFile EventFile::create(const std::string& dir, double wall_time) {
  const std::string stem =
      dir + "/events.out.tfevents." + std::to_string(static_cast<int64_t>(std::floor(wall_time))) +
      "." + host_name();
  std::string path = stem;
  for (int n = 2; !create_exclusively(path); ++n) path = stem + "." + std::to_string(n);
  EventFile file(CheckedFile(path, CheckedFile::Mode::kAppend), 0);
  ProtoWriter event;
  event.float64(1, wall_time).bytes(3, "brain.Event:2");  // Event.wall_time, Event.file_version
  file.write(event);
  return file;
}

EventFile EventFile::reopen(const std::string& path, uint64_t bytes) {
  std::error_code ec;
  const uintmax_t size = fs::file_size(path, ec);
  if (ec) throw RuntimeFailure("cannot open " + path + ": " + ec.message());
  if (size < bytes)
    throw RuntimeFailure(path + " holds " + std::to_string(size) + " bytes, fewer than the " +
                         std::to_string(bytes) + " the checkpoint recorded (cut or replaced since)");
  fs::resize_file(path, bytes, ec);
  if (ec) throw RuntimeFailure("cannot cut " + path + " back to the checkpoint: " + ec.message());
  return EventFile(CheckedFile(path, CheckedFile::Mode::kAppend), bytes);
}

void EventFile::write(const ProtoWriter& event) {
  const std::string record = tfrecord(event.str());
  file_ << record;
  file_.flush();
  size_ += record.size();
}

}  // namespace rlrun
