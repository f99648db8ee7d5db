#include "rlrun/envs/sumo/worker_protocol.hpp"

#include <sys/socket.h>

#include <cerrno>

namespace rlrun::traffic::wire {

void write_reading(Writer& w, const NetworkReading& r) {
  w.f64(r.time).i32(static_cast<int32_t>(r.lanes.size()));
  for (const LaneReading& l : r.lanes) w.i32(l.vehicles).i32(l.halting).f64(l.vehicle_length);
  w.i32(static_cast<int32_t>(r.edges.size()));
  for (const LaneReading& e : r.edges) w.i32(e.vehicles).i32(e.halting).f64(e.mean_speed);
  w.i32(static_cast<int32_t>(r.vehicles.size()));
  for (const VehicleReading& v : r.vehicles)
    w.str(v.id)
        .str(v.lane)
        .f64(v.speed)
        .f64(v.allowed_speed)
        .f64(v.accumulated_waiting)
        .f64(v.x)
        .f64(v.y)
        .f64(v.angle);
}

void read_reading(Reader& r, NetworkReading& out) {
  out.time = r.f64();
  out.lanes.resize(static_cast<size_t>(std::max(0, r.i32())));
  for (LaneReading& l : out.lanes) {
    l.vehicles = r.i32();
    l.halting = r.i32();
    l.vehicle_length = r.f64();
  }
  out.edges.resize(static_cast<size_t>(std::max(0, r.i32())));
  for (LaneReading& e : out.edges) {
    e.vehicles = r.i32();
    e.halting = r.i32();
    e.mean_speed = r.f64();
  }
  out.vehicles.resize(static_cast<size_t>(std::max(0, r.i32())));
  for (VehicleReading& v : out.vehicles) {
    v.id = r.str();
    v.lane = r.str();
    v.speed = r.f64();
    v.allowed_speed = r.f64();
    v.accumulated_waiting = r.f64();
    v.x = r.f64();
    v.y = r.f64();
    v.angle = r.f64();
  }
}

bool send_message(int fd, const std::vector<char>& framed) {
  size_t done = 0;
  while (done < framed.size()) {
    const ssize_t n = send(fd, framed.data() + done, framed.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

namespace {

bool receive_exact(int fd, char* data, size_t size, const std::function<void()>& wait) {
  size_t done = 0;
  while (done < size) {
    const ssize_t n = recv(fd, data + done, size - done, wait ? MSG_DONTWAIT : 0);
    if (n < 0 && wait && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      wait();
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

}  // namespace

bool receive_message(int fd, std::vector<char>& body, const std::function<void()>& wait) {
  uint32_t n = 0;
  if (!receive_exact(fd, reinterpret_cast<char*>(&n), 4, wait)) return false;
  // A reading of a city map with every vehicle is a few MB; more is a broken stream.
  if (n > (1u << 30)) return false;
  body.resize(n);
  return receive_exact(fd, body.data(), n, wait);
}

}  // namespace rlrun::traffic::wire
