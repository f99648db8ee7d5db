// A small stand-in for libFuzzer's main, so the fuzz targets build with any compiler and a
// short deterministic run is part of the normal test suite (fuzz/CMakeLists.txt):
//   fuzz_<target> [-runs=N] [-seed=S] [-max_len=N] [-timeout=S] [-dict=FILE] CORPUS...
// runs every file of the corpus directories (or files) once, then N inputs made from them by
// seeded mutations (bit flips, byte changes, inserts, erases, copies, splices, dictionary
// tokens) — the same inputs for the same seed, on every machine. Options libFuzzer has mean
// the same here; others are ignored. An input that crashes, trips a sanitizer or runs longer
// than -timeout seconds is saved as ./crash-standalone (or timeout-standalone) for replay
// with `fuzz_<target> crash-standalone` or a libFuzzer build.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
extern "C" __attribute__((weak)) int LLVMFuzzerInitialize(int* argc, char*** argv);

namespace {

using Bytes = std::vector<uint8_t>;

// The input being run, for the signal handlers (which may only write(2) it out).
const Bytes* g_current = nullptr;

void save_current(const char* file) {
  if (!g_current) return;
  const int fd = open(file, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) return;
  if (!g_current->empty()) {
    const ssize_t ignored = write(fd, g_current->data(), g_current->size());
    (void)ignored;
  }
  close(fd);
}

void on_crash(int sig) {
  save_current("crash-standalone");
  const char message[] = "standalone fuzz driver: crash; input saved as crash-standalone\n";
  const ssize_t ignored = write(STDERR_FILENO, message, sizeof(message) - 1);
  (void)ignored;
  signal(sig, SIG_DFL);
  raise(sig);
}

void on_timeout(int) {
  save_current("timeout-standalone");
  const char message[] = "standalone fuzz driver: timeout; input saved as timeout-standalone\n";
  const ssize_t ignored = write(STDERR_FILENO, message, sizeof(message) - 1);
  (void)ignored;
  _exit(70);
}

// splitmix64: small, seedable, the same everywhere.
struct Rng {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  size_t below(size_t n) { return n == 0 ? 0 : static_cast<size_t>(next() % n); }
};

Bytes read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// libFuzzer's dictionary format: one "token" per line (optionally name="token"), \xNN and
// \\ \" escapes, # comments.
std::vector<Bytes> read_dictionary(const std::string& path) {
  std::vector<Bytes> tokens;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    const size_t open = line.find('"');
    const size_t close = line.rfind('"');
    if (line.empty() || line[0] == '#' || open == std::string::npos || close <= open) continue;
    Bytes token;
    for (size_t i = open + 1; i < close; ++i) {
      if (line[i] == '\\' && i + 1 < close) {
        if (line[i + 1] == 'x' && i + 3 < close) {
          token.push_back(static_cast<uint8_t>(std::stoi(line.substr(i + 2, 2), nullptr, 16)));
          i += 3;
        } else {
          token.push_back(static_cast<uint8_t>(line[++i]));
        }
      } else {
        token.push_back(static_cast<uint8_t>(line[i]));
      }
    }
    tokens.push_back(token);
  }
  return tokens;
}

void mutate(Bytes& data, const std::vector<Bytes>& corpus, const std::vector<Bytes>& dictionary,
            size_t max_len, Rng& rng) {
  static const uint8_t kInteresting[] = {0,   1,   0x7f, 0x80, 0xff, '0', '9', '-', ' ',  '\n',
                                         ':', ',', '[',  ']',  '{',  '}', '(', ')', '\'', '"'};
  const int steps = 1 + static_cast<int>(rng.below(4));
  for (int s = 0; s < steps; ++s) {
    const size_t at = rng.below(data.size() + 1);
    switch (rng.below(8)) {
      case 0:  // flip a bit
        if (!data.empty()) data[rng.below(data.size())] ^= static_cast<uint8_t>(1u << rng.below(8));
        break;
      case 1:  // set a byte
        if (!data.empty()) data[rng.below(data.size())] = static_cast<uint8_t>(rng.next());
        break;
      case 2:  // an interesting byte
        if (!data.empty())
          data[rng.below(data.size())] = kInteresting[rng.below(sizeof(kInteresting))];
        break;
      case 3: {  // insert random bytes
        const size_t n = 1 + rng.below(8);
        for (size_t i = 0; i < n; ++i)
          data.insert(data.begin() + static_cast<long>(at), static_cast<uint8_t>(rng.next()));
        break;
      }
      case 4: {  // erase a range
        if (data.empty()) break;
        const size_t from = rng.below(data.size());
        const size_t n = 1 + rng.below(std::min<size_t>(data.size() - from, 16));
        data.erase(data.begin() + static_cast<long>(from),
                   data.begin() + static_cast<long>(from + n));
        break;
      }
      case 5: {  // copy a range of the input elsewhere
        if (data.empty()) break;
        const size_t from = rng.below(data.size());
        const size_t n = 1 + rng.below(std::min<size_t>(data.size() - from, 32));
        const Bytes piece(data.begin() + static_cast<long>(from),
                          data.begin() + static_cast<long>(from + n));
        data.insert(data.begin() + static_cast<long>(std::min(at, data.size())), piece.begin(),
                    piece.end());
        break;
      }
      case 6: {  // splice: the head of this input, the tail of another
        const Bytes& other = corpus[rng.below(corpus.size())];
        if (other.empty()) break;
        const size_t from = rng.below(other.size());
        data.resize(std::min(at, data.size()));
        data.insert(data.end(), other.begin() + static_cast<long>(from), other.end());
        break;
      }
      default:  // a dictionary token
        if (dictionary.empty()) break;
        const Bytes& token = dictionary[rng.below(dictionary.size())];
        data.insert(data.begin() + static_cast<long>(at), token.begin(), token.end());
        break;
    }
  }
  if (data.size() > max_len) data.resize(max_len);
}

bool option(const char* arg, const char* name, std::string& value) {
  const size_t n = std::strlen(name);
  if (std::strncmp(arg, name, n) != 0 || arg[n] != '=') return false;
  value = arg + n + 1;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  long runs = 0;
  uint64_t seed = 1;
  size_t max_len = 4096;
  unsigned timeout = 0;
  std::vector<Bytes> dictionary;
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    std::string value;
    if (option(argv[i], "-runs", value)) {
      runs = std::stol(value);
    } else if (option(argv[i], "-seed", value)) {
      seed = std::stoull(value);
    } else if (option(argv[i], "-max_len", value)) {
      max_len = std::stoul(value);
    } else if (option(argv[i], "-timeout", value)) {
      timeout = static_cast<unsigned>(std::stoul(value));
    } else if (option(argv[i], "-dict", value)) {
      dictionary = read_dictionary(value);
    } else if (argv[i][0] == '-') {
      continue;  // a libFuzzer option this driver does not implement
    } else if (std::filesystem::is_directory(argv[i])) {
      for (const auto& entry : std::filesystem::directory_iterator(argv[i]))
        if (entry.is_regular_file()) files.push_back(entry.path());
    } else {
      files.push_back(argv[i]);
    }
  }
  std::sort(files.begin(), files.end());  // directory order differs between file systems
  std::vector<Bytes> corpus;
  for (const auto& f : files) corpus.push_back(read_file(f));
  if (corpus.empty()) corpus.push_back({});

  for (int sig : {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL}) signal(sig, on_crash);
  signal(SIGALRM, on_timeout);
  const auto run_one = [&](const Bytes& input) {
    g_current = &input;
    if (timeout) alarm(timeout);
    LLVMFuzzerTestOneInput(input.data(), input.size());
    if (timeout) alarm(0);
    g_current = nullptr;
  };
  const auto start = std::chrono::steady_clock::now();
  for (const Bytes& input : corpus) run_one(input);
  Rng rng{seed};
  for (long r = 0; r < runs; ++r) {
    Bytes input = corpus[rng.below(corpus.size())];
    mutate(input, corpus, dictionary, max_len, rng);
    run_one(input);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "standalone fuzz driver: %zu corpus inputs + %ld mutations (seed %llu) in %.1f s, "
      "no crash\n",
      corpus.size(), runs, static_cast<unsigned long long>(seed), seconds);
  return 0;
}
