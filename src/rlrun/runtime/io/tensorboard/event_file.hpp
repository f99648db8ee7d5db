#pragma once
// One TensorBoard event file: `events.out.tfevents.<unix time>.<host>`, a TFRecord file of
// serialized `Event` messages (tensorboard/compat/proto/event.proto). Each record is
//     uint64 length | uint32 masked CRC-32C of the length | data | uint32 masked CRC-32C of data
// (little-endian; tensorflow/core/lib/io/record_writer.cc). The first event names the format
// ("brain.Event:2"), as TensorFlow's and PyTorch's writers do; TensorBoard reads every such
// file in a run's directory in name order.
#include <cstdint>
#include <string>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/protobuf_writer.hpp"

namespace rlrun {

class EventFile {
 public:
  // A new event file in `dir`, starting with the file_version event.
  static EventFile create(const DirHandle& dir, double wall_time);
  // The existing event file `name` in `dir` cut back to its first `bytes` bytes (a resumed run
  // continues where its checkpoint was written; records written after it would appear twice).
  // A checkpoint names it: it must be a regular file, not a link (core/dir_handle.hpp). Throws
  // RuntimeFailure when it is not, or is shorter than that.
  static EventFile reopen(const DirHandle& dir, const std::string& name, uint64_t bytes);

  // Appends one Event record and writes it through (TensorBoard shows it on its next reload;
  // a full disk is a RuntimeFailure naming the file).
  void write(const ProtoWriter& event);

  const std::string& path() const { return file_.path(); }
  uint64_t size() const { return size_; }

 private:
  EventFile(CheckedFile file, uint64_t size) : file_(std::move(file)), size_(size) {}
  CheckedFile file_;
  uint64_t size_ = 0;
};

// The TFRecord framing of one record (exposed for tests).
std::string tfrecord(const std::string& data);

}  // namespace rlrun
