#include "rlrun/envs/python/python_env.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <sstream>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/space_json.hpp"
#include "rlrun/envs/python/python_protocol.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

// worker.py's text, compiled in by CMake (build/generated/python_worker_script.cpp).
const char* python_worker_script();

namespace protocol = python_protocol;
using nlohmann::json;

namespace {

template <class T>
T take(const std::vector<std::byte>& body, size_t& at) {
  if (at + sizeof(T) > body.size()) throw std::out_of_range("reply too short");
  T value;
  std::memcpy(&value, body.data() + at, sizeof(T));
  at += sizeof(T);
  return value;
}

}  // namespace

struct PythonEnv::Handshake {
  Space observation_space, action_space;
  int obs_dim = 0, act_dim = 0;
  int num_agents = 1;
  std::vector<std::string> agent_names;  // a PettingZoo env's; empty for a Gymnasium env
  bool can_render = false;
  double render_fps = 30.0;
  std::optional<int> max_episode_steps;
};

PythonEnv::PythonEnv(std::string target, std::string kwargs_json, const std::string& python,
                     double startup_timeout, const PettingZooSettings& pettingzoo)
    : PythonEnv(std::move(target), std::move(kwargs_json),
                std::make_unique<PythonWorker>(python, python_worker_script()), startup_timeout,
                pettingzoo) {}

PythonEnv::PythonEnv(std::string target, std::string kwargs_json,
                     std::unique_ptr<PythonWorker> worker, double startup_timeout,
                     const PettingZooSettings& pettingzoo)
    : target_(std::move(target)), startup_timeout_(startup_timeout), worker_(std::move(worker)) {
  // Keys every Python env declares up front: the Monitor writes is_success into
  // <i>.monitor.csv only for keys known when it is built (empty when the env never reports it).
  is_success_ = info_.add_key("is_success");
  const json spec = {
      {"target", target_},
      {"kwargs", json::parse(kwargs_json)},
      {"turn_based",
       {{"opponent", pettingzoo.opponent}, {"learner_side", pettingzoo.learner_side}}},
      {"agent_indicator", pettingzoo.agent_indicator}};
  const std::string text = spec.dump();
  const uint32_t length = static_cast<uint32_t>(text.size());
  std::vector<std::byte> message(4 + text.size());
  std::memcpy(message.data(), &length, 4);
  std::memcpy(message.data() + 4, text.data(), text.size());
  if (!worker_->write(message, waiting("to start"))) worker_gone("while starting");
}

PythonEnv::~PythonEnv() = default;

WorkerWait PythonEnv::waiting(const char* what) const {
  WorkerWait wait;
  wait.who = target_ + " (Python worker pid " + std::to_string(worker_->pid()) + ")";
  wait.what = what;
  if (handshake_) return wait;
  // Before the handshake: the interpreter imports the module and builds the env.
  wait.starting = true;
  wait.since = worker_->started();
  wait.timeout_seconds = startup_timeout_;
  std::ostringstream seconds;
  seconds << startup_timeout_;
  wait.timeout_message =
      target_ + ": its Python worker (pid " + std::to_string(worker_->pid()) + ", " +
      worker_->python() + ") has not finished starting within " + seconds.str() +
      " s (env.startup_timeout), so it was stopped: importing the module or building the env "
      "(its __init__) hangs or takes longer. Raise env.startup_timeout if it needs more time";
  return wait;
}

void PythonEnv::ready() const {
  if (handshake_) return;
  const WorkerWait starting = waiting("to start");
  uint32_t length = 0;
  if (!worker_->read(std::as_writable_bytes(std::span(&length, 1)), starting))
    worker_gone("while starting");
  if (length > protocol::kMaxHandshakeBytes)
    fail("its worker sent a handshake of " + std::to_string(length) + " bytes");
  std::string text(length, '\0');
  if (!worker_->read(std::as_writable_bytes(std::span(text.data(), text.size())), starting))
    worker_gone("while starting");
  json reply;
  try {
    reply = json::parse(text);
  } catch (const json::exception& e) {
    fail(std::string("its worker sent a handshake that is not JSON: ") + e.what());
  }
  if (!reply.value("ok", false)) {
    throw RuntimeFailure(target_ + " (Python worker pid " + std::to_string(worker_->pid()) + ", " +
                         worker_->python() + ") could not be built:\n" +
                         reply.value("error", std::string("(no message)")));
  }
  auto h = std::make_unique<Handshake>();
  // A space rlrun cannot learn on (Discrete(2**62)) is the env's problem, named as such.
  const auto space = [&](const char* name) {
    try {
      return space_from_json(reply.at(name));
    } catch (const std::invalid_argument& e) {
      fail(std::string("its ") + name + ": " + e.what());
    }
  };
  try {
    if (reply.at("protocol").get<int>() != protocol::kVersion)
      throw std::invalid_argument("protocol version differs");
    h->observation_space = space("observation_space");
    h->action_space = space("action_space");
    h->obs_dim = reply.at("obs_dim").get<int>();
    h->act_dim = reply.at("act_dim").get<int>();
    if (h->obs_dim != h->observation_space.flat_dim() || h->act_dim != h->action_space.flat_dim())
      throw std::invalid_argument("sizes disagree with the spaces");
    h->num_agents = reply.value("num_agents", 1);
    if (h->num_agents < 1 || h->num_agents > protocol::kMaxAgents)
      throw std::invalid_argument(std::to_string(h->num_agents) + " agents (at most " +
                                  std::to_string(protocol::kMaxAgents) + ")");
    if (reply.contains("agents") && reply["agents"].is_array() && h->num_agents > 1) {
      h->agent_names = reply["agents"].get<std::vector<std::string>>();
      if (static_cast<int>(h->agent_names.size()) != h->num_agents)
        throw std::invalid_argument("agent names disagree with num_agents");
    }
    h->can_render = reply.value("render_mode", json()).is_string() &&
                    reply["render_mode"].get<std::string>() == "rgb_array";
    h->render_fps = reply.value("render_fps", 30.0);
    if (!(h->render_fps > 0 && h->render_fps <= 1000)) h->render_fps = 30.0;
    if (reply.contains("max_episode_steps") && reply["max_episode_steps"].is_number_integer())
      h->max_episode_steps = reply["max_episode_steps"].get<int>();
  } catch (const RuntimeFailure&) {
    throw;
  } catch (const std::exception& e) {
    fail(std::string("its worker's handshake does not describe the env: ") + e.what());
  }
  request_.assign(protocol::request_bytes(h->act_dim * h->num_agents), std::byte{0});
  worker_->set_request_bytes(request_.size());
  handshake_ = std::move(h);
}

void PythonEnv::fail(const std::string& what) const {
  throw RuntimeFailure(target_ + " (Python worker pid " + std::to_string(worker_->pid()) +
                       "): " + what);
}

void PythonEnv::worker_gone(const char* during) const {
  const std::string ended = worker_->how_it_ended();
  std::string where = during;
  if (was_reset_)
    where += " (step " + std::to_string(step_) + " of episode " + std::to_string(episode_) + ")";
  throw RuntimeFailure(target_ + ": its Python worker (pid " + std::to_string(worker_->pid()) +
                       ", " + worker_->python() + ") " + ended + " " + where +
                       "; its output above shows why (a crash prints the Python stack)");
}

void PythonEnv::send_request() const {
  worker_->set_awaiting_reply(true);
  if (!worker_->write(request_, waiting("to take a request")))
    worker_gone("while sending a request");
}

const std::vector<std::byte>& PythonEnv::receive(const char* during) const {
  const WorkerWait wait = waiting(during);
  std::byte header[5];
  if (!worker_->read(header, wait)) worker_gone(during);
  uint32_t length = 0;
  std::memcpy(&length, header + 1, 4);
  const char status = static_cast<char>(header[0]);
  const uint32_t limit =
      status == protocol::kError ? protocol::kMaxErrorBytes : protocol::kMaxReplyBytes;
  if ((status != protocol::kOk && status != protocol::kError) || length > limit)
    fail(std::string("its worker sent a malformed reply ") + during);
  reply_.resize(length);
  if (!worker_->read(reply_, wait)) worker_gone(during);
  worker_->set_awaiting_reply(false);
  if (status == protocol::kError) {
    std::string where = during;
    if (was_reset_)
      where += " at step " + std::to_string(step_) + " of episode " + std::to_string(episode_);
    throw RuntimeFailure(target_ + " (Python worker pid " + std::to_string(worker_->pid()) +
                         ") failed " + where + ":\n" +
                         std::string(reinterpret_cast<const char*>(reply_.data()), reply_.size()));
  }
  return reply_;
}

const Space& PythonEnv::observation_space() const {
  ready();
  return handshake_->observation_space;
}

const Space& PythonEnv::action_space() const {
  ready();
  return handshake_->action_space;
}

std::optional<int> PythonEnv::registered_time_limit() const {
  ready();
  return handshake_->max_episode_steps;
}

void PythonEnv::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  ready();
  request_[0] = static_cast<std::byte>(protocol::kReset);
  request_[1] = static_cast<std::byte>(seed.has_value());
  const uint64_t value = seed.value_or(0);
  std::memcpy(request_.data() + 2, &value, 8);
  send_request();
  ++episode_;
  step_ = 0;
  was_reset_ = true;
  reset_results_.resize(static_cast<size_t>(handshake_->num_agents));
  read_step_reply(obs, reset_results_, "in reset()");
}

int PythonEnv::num_agents() const {
  ready();
  return handshake_->num_agents;
}

std::string PythonEnv::agent_name(int agent) const {
  ready();
  if (handshake_->agent_names.empty()) return "agent_" + std::to_string(agent);
  return handshake_->agent_names.at(static_cast<size_t>(agent));
}

void PythonEnv::step_agents(std::span<const float> actions, std::span<float> obs,
                            std::span<StepResult> results) {
  start_step_agents(actions);
  finish_step_agents(obs, results);
}

void PythonEnv::start_step_agents(std::span<const float> actions) {
  ready();
  const size_t floats = static_cast<size_t>(handshake_->act_dim) * handshake_->num_agents;
  if (actions.size() != floats)
    throw std::invalid_argument(target_ + ": step_agents() takes " + std::to_string(floats) +
                                " action floats, got " + std::to_string(actions.size()));
  request_[0] = static_cast<std::byte>(protocol::kStep);
  std::memcpy(request_.data() + 1, actions.data(), actions.size_bytes());
  send_request();
  ++step_;
}

void PythonEnv::finish_step_agents(std::span<float> obs, std::span<StepResult> results) {
  read_step_reply(obs, results, "in step()");
}

StepResult PythonEnv::step(std::span<const float> action, std::span<float> obs) {
  start_step(action);
  return finish_step(obs);
}

void PythonEnv::start_step(std::span<const float> action) {
  ready();
  if (handshake_->num_agents != 1)
    throw std::invalid_argument(target_ + " has " + std::to_string(handshake_->num_agents) +
                                " agents: step them with step_agents()");
  start_step_agents(action);
}

StepResult PythonEnv::finish_step(std::span<float> obs) {
  StepResult result;
  read_step_reply(obs, std::span(&result, 1), "in step()");
  return result;
}

void PythonEnv::read_step_reply(std::span<float> obs, std::span<StepResult> results,
                                const char* during) {
  const std::vector<std::byte>& body = receive(during);
  const size_t agents = static_cast<size_t>(handshake_->num_agents);
  const size_t obs_floats = static_cast<size_t>(handshake_->obs_dim) * agents;
  const size_t obs_bytes = 4 * obs_floats;
  if (obs.size() != obs_floats || results.size() != agents)
    throw std::invalid_argument(target_ + ": buffers for " + std::to_string(results.size()) +
                                " agents and " + std::to_string(obs.size()) +
                                " observation floats; the env has " + std::to_string(agents) +
                                " agents of " + std::to_string(handshake_->obs_dim));
  try {
    size_t at = 0;
    for (StepResult& r : results) r.reward = take<double>(body, at);
    for (StepResult& r : results) r.terminated = take<uint8_t>(body, at) != 0;
    for (StepResult& r : results) r.truncated = take<uint8_t>(body, at) != 0;
    if (at + obs_bytes > body.size()) throw std::out_of_range("observation");
    std::memcpy(obs.data(), body.data() + at, obs_bytes);
    at += obs_bytes;
    const int new_keys = take<uint16_t>(body, at);
    for (int k = 0; k < new_keys; ++k) {
      const int length = take<uint16_t>(body, at);
      if (at + length > body.size()) throw std::out_of_range("info key");
      const std::string name(reinterpret_cast<const char*>(body.data() + at), length);
      at += length;
      if (static_cast<int>(info_index_.size()) >= protocol::kMaxInfoKeys)
        throw std::out_of_range("too many info keys");
      info_index_.push_back(info_.add_key(name));
    }
    info_.clear();
    const int values = take<uint16_t>(body, at);
    for (int k = 0; k < values; ++k) {
      const int index = take<uint16_t>(body, at);
      const double value = take<double>(body, at);
      if (index >= static_cast<int>(info_index_.size())) throw std::out_of_range("info index");
      info_.set(info_index_[index], value);
    }
    if (at != body.size()) throw std::out_of_range("trailing bytes");
  } catch (const std::out_of_range& e) {
    fail(std::string("its worker sent a malformed reply ") + during + " (" + e.what() + ")");
  }
}

bool PythonEnv::fetch_frame() const {
  ready();
  if (!handshake_->can_render) return false;
  request_[0] = static_cast<std::byte>(protocol::kRender);
  send_request();
  const std::vector<std::byte>& body = receive("in render()");
  size_t at = 0;
  try {
    const uint32_t height = take<uint32_t>(body, at);
    const uint32_t width = take<uint32_t>(body, at);
    if (height > 4096 || width > 4096 || body.size() != at + size_t{height} * width * 3)
      throw std::out_of_range("frame size");
    if (height == 0 || width == 0) return false;
    frame_height_ = static_cast<int>(height);
    frame_width_ = static_cast<int>(width);
    frame_rgb_.resize(body.size() - at);
    std::memcpy(frame_rgb_.data(), body.data() + at, frame_rgb_.size());
  } catch (const std::out_of_range& e) {
    fail(std::string("its worker sent a malformed frame (") + e.what() + ")");
  }
  return true;
}

// The env's own frame size once it has drawn one. Before the first reset the env may have no
// state to draw (Gymnasium's classic envs return None), so the size is asked for then.
RenderSpec PythonEnv::render_spec() const {
  ready();
  if (!handshake_->can_render || render_probe_failed_) return {};
  if (frame_width_ == 0 && was_reset_) {
    // Asking is not rendering: an env whose render() fails here (SB3's make_vec_env sets
    // render_mode="rgb_array", and Gymnasium's classic envs then need pygame) is one that does
    // not render; training goes on, and recording it says why.
    try {
      fetch_frame();
    } catch (const RuntimeFailure& e) {
      render_probe_failed_ = true;
      // The error's last line: a Python traceback ends with the exception and its message.
      std::string what = e.what();
      while (!what.empty() && what.back() == '\n') what.pop_back();
      const std::string last = what.substr(what.find_last_of('\n') + 1);  // npos + 1 == 0
      std::fprintf(
          stderr, "note: %s: render() failed, so it is taken as an env that does not render (%s)\n",
          target_.c_str(), last.c_str());
      return {};
    }
  }
  if (frame_width_ == 0) return {600, 400, handshake_->render_fps};  // Gymnasium's usual size
  // Even sizes, as H.264 in yuv420p needs (an odd frame, connect four's 891 x 774 in PettingZoo,
  // is drawn letterboxed into the next even size).
  return {(frame_width_ + 1) / 2 * 2, (frame_height_ + 1) / 2 * 2, handshake_->render_fps};
}

// The env's rgb_array frame, scaled to the frame (nearest pixel) and letterboxed in black.
bool PythonEnv::render(Frame& frame) const {
  if (!fetch_frame()) return false;
  const double scale = std::min(static_cast<double>(frame.width()) / frame_width_,
                                static_cast<double>(frame.height()) / frame_height_);
  const int w = std::max(1, static_cast<int>(std::lround(frame_width_ * scale)));
  const int h = std::max(1, static_cast<int>(std::lround(frame_height_ * scale)));
  const int x0 = (frame.width() - w) / 2, y0 = (frame.height() - h) / 2;
  uint32_t* pixels = frame.pixels();
  const int stride = frame.stride_pixels();
  for (int y = 0; y < frame.height(); ++y)
    for (int x = 0; x < frame.width(); ++x) {
      uint32_t rgb = 0;
      if (x >= x0 && x < x0 + w && y >= y0 && y < y0 + h) {
        const int sx = std::min(frame_width_ - 1, static_cast<int>((x - x0) / scale));
        const int sy = std::min(frame_height_ - 1, static_cast<int>((y - y0) / scale));
        const uint8_t* p = frame_rgb_.data() + (static_cast<size_t>(sy) * frame_width_ + sx) * 3;
        rgb = (uint32_t{p[0]} << 16) | (uint32_t{p[1]} << 8) | p[2];
      }
      pixels[static_cast<size_t>(y) * stride + x] = rgb;
    }
  frame.mark_dirty();
  return true;
}

}  // namespace rlrun
