#pragma once
// The messages between a traffic env and its SUMO worker (rlrun-sumo-worker, a program of
// rlrun's own that drives one SUMO — over TraCI, or inside itself with libsumo — and answers on
// a socket). Every SumoConnection call (sumo_connection.hpp) is one request:
//
//   [u32 length][u8 op][fields...]    little-endian; strings as u32 length + bytes
//
// Requests that need no answer (subscribe, set_light_state, switch_light, use_program)
// are only sent; the worker keeps the first error and reports it with the next answer, so a
// decision costs one round trip however many lights switch. Answers start with a status:
// kOk, or kError followed by the message and the last lines of SUMO's output.
//
// The worker is rlrun's own program started with fork + exec (never a bare fork: rlrun's other
// threads may hold locks), and it trusts its parent: this is not a network protocol.
#include <cstdint>
#include <cstring>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "rlrun/envs/sumo/sumo_connection.hpp"

namespace rlrun::traffic::wire {

enum Op : uint8_t {
  kStart = 1,          // backend, SUMO's arguments -> status, pid
  kSubscribe,          // lanes, edges -> (none)
  kSubscribeVehicles,  // junction -> status, reading
  kAdvance,            // time -> status, reading
  kSetLightState,      // tls, state -> (none)
  kSwitchLight,        // tls, yellow, seconds, green -> (none)
  kUseProgram,         // tls, program -> (none)
  kFinish,             // -> status
  kOutputTail,         // -> status, text
};

enum Status : uint8_t { kOk = 0, kError = 1 };

// A message being written.
class Writer {
 public:
  explicit Writer(uint8_t op) { bytes_.resize(4), u8(op); }
  Writer& u8(uint8_t v) { return raw(&v, 1); }
  Writer& i32(int32_t v) { return raw(&v, 4); }
  Writer& f64(double v) { return raw(&v, 8); }
  Writer& str(const std::string& s) {
    i32(static_cast<int32_t>(s.size()));
    return raw(s.data(), s.size());
  }
  Writer& strings(const std::vector<std::string>& list) {
    i32(static_cast<int32_t>(list.size()));
    for (const std::string& s : list) str(s);
    return *this;
  }
  // The framed bytes: the length prefix filled in.
  const std::vector<char>& framed() {
    const uint32_t n = static_cast<uint32_t>(bytes_.size() - 4);
    std::memcpy(bytes_.data(), &n, 4);
    return bytes_;
  }

 private:
  Writer& raw(const void* p, size_t n) {
    const size_t at = bytes_.size();
    bytes_.resize(at + n);
    if (n > 0) std::memcpy(bytes_.data() + at, p, n);
    return *this;
  }
  std::vector<char> bytes_;
};

// A message being read (its body, after the length prefix). Reading past the end throws.
class Reader {
 public:
  explicit Reader(std::vector<char> body) : body_(std::move(body)) {}
  uint8_t u8() {
    uint8_t v;
    raw(&v, 1);
    return v;
  }
  int32_t i32() {
    int32_t v;
    raw(&v, 4);
    return v;
  }
  double f64() {
    double v;
    raw(&v, 8);
    return v;
  }
  std::string str() {
    const int32_t n = i32();
    if (n < 0 || static_cast<size_t>(n) > body_.size() - at_)
      throw std::runtime_error("SUMO worker: bad message");
    std::string s(body_.data() + at_, static_cast<size_t>(n));
    at_ += static_cast<size_t>(n);
    return s;
  }
  std::vector<std::string> strings() {
    const int32_t n = i32();
    if (n < 0 || static_cast<size_t>(n) > body_.size())
      throw std::runtime_error("SUMO worker: bad message");
    std::vector<std::string> out(static_cast<size_t>(n));
    for (std::string& s : out) s = str();
    return out;
  }

 private:
  void raw(void* p, size_t n) {
    if (n > body_.size() - at_) throw std::runtime_error("SUMO worker: truncated message");
    std::memcpy(p, body_.data() + at_, n);
    at_ += n;
  }
  std::vector<char> body_;
  size_t at_ = 0;
};

void write_reading(Writer& w, const NetworkReading& r);
void read_reading(Reader& r, NetworkReading& out);

// Whole messages over a stream socket; false when the other side has gone. With `wait`,
// receive_message calls it whenever nothing has arrived (rlrun polls for Ctrl-C there,
// core/worker_wait.hpp) instead of blocking in recv.
bool send_message(int fd, const std::vector<char>& framed);
bool receive_message(int fd, std::vector<char>& body, const std::function<void()>& wait = {});

}  // namespace rlrun::traffic::wire
