#include "rlrun/runtime/io/tensorboard/event_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <optional>

#include "rlrun/core/crc32c.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/regular_file.hpp"

namespace rlrun {

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

EventFile EventFile::create(const DirHandle& dir, double wall_time) {
  const std::string stem = "events.out.tfevents." +
                           std::to_string(static_cast<int64_t>(std::floor(wall_time))) + "." +
                           host_name();
  // Only a name that does not exist yet (never another run's file).
  std::optional<CheckedFile> created = dir.create_new(stem);
  for (int n = 2; !created; ++n) created = dir.create_new(stem + "." + std::to_string(n));
  EventFile file(std::move(*created), 0);
  ProtoWriter event;
  event.float64(1, wall_time).bytes(3, "brain.Event:2");  // Event.wall_time, Event.file_version
  file.write(event);
  return file;
}

EventFile EventFile::reopen(const DirHandle& dir, const std::string& name, uint64_t bytes) {
  const std::string path = dir.child(name);
  FileDescriptor fd = open_regular_file(dir.fd(), name, O_WRONLY | O_APPEND, path);
  if (!fd) throw RuntimeFailure("cannot open " + path + ": it is gone");
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0)
    throw RuntimeFailure("cannot open " + path + ": " + describe_errno(errno));
  if (static_cast<uint64_t>(st.st_size) < bytes)
    throw RuntimeFailure(path + " holds " + std::to_string(st.st_size) + " bytes, fewer than the " +
                         std::to_string(bytes) +
                         " the checkpoint recorded (cut or replaced since)");
  if (::ftruncate(fd.get(), static_cast<off_t>(bytes)) != 0)
    throw RuntimeFailure("cannot cut " + path +
                         " back to the checkpoint: " + describe_errno(errno));
  return EventFile(CheckedFile::adopt(std::move(fd), path), bytes);
}

void EventFile::write(const ProtoWriter& event) {
  const std::string record = tfrecord(event.str());
  file_ << record;
  file_.flush();
  size_ += record.size();
}

}  // namespace rlrun
