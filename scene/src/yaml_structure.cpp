#include "yaml_structure.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <set>
#include <thread>
#include <vector>

#include "scene/errors.hpp"
#include "scene/yaml_text.hpp"

namespace scene {

namespace {

// A hostile file can nest [[[[...]]]] deep enough to exhaust the stack of a
// recursive walk; no scene is deeper than a handful of levels.
constexpr int kMaxDepth = 64;

std::string at(const std::string& origin, const YAML::Mark& m) {
  return m.line >= 0 ? origin + ":" + std::to_string(m.line + 1) : origin;
}

void check_node(const YAML::Node& n, const std::string& origin, const std::string& path,
                int depth) {
  if (depth > kMaxDepth)
    throw InputError(at(origin, n.Mark()) + ": YAML nested deeper than " +
                     std::to_string(kMaxDepth) + " levels");
  if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i)
      check_node(n[i], origin, path + "[" + std::to_string(i) + "]", depth + 1);
    return;
  }
  if (!n.IsMap()) return;
  std::set<std::string> seen;
  for (const auto& kv : n) {
    const YAML::Node key = kv.first;
    if (!key.IsScalar())
      throw InputError(at(origin, key.Mark()) + ": " +
                       (path.empty() ? "top level" : "key '" + path + "'") +
                       ": expected plain scalar keys, got a " +
                       (key.IsMap()        ? "mapping"
                        : key.IsSequence() ? "list"
                                           : "null") +
                       " as a key");
    const std::string k = key.Scalar();
    const std::string full = path.empty() ? k : path + "." + k;
    if (!seen.insert(k).second)
      throw InputError(at(origin, key.Mark()) + ": key '" + full +
                       "': duplicate key (each key may appear once)");
    check_node(kv.second, origin, full, depth + 1);
  }
}

// YAML text is printable Unicode (YAML 1.2, c-printable) in UTF-8; yaml-cpp
// 0.7 loops for ever, allocating, on some binary junk, so such bytes are
// refused before it sees them.
void check_printable_utf8(const std::string& text, const std::string& origin) {
  int line = 1;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const auto refuse = [&](const std::string& what) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", c);
      throw InputError(origin + ":" + std::to_string(line) + ": not a YAML text file: " + what +
                       " (byte " + hex + " at offset " + std::to_string(i) + ")");
    };
    if (c == '\n') ++line;
    if (c < 0x80) {
      if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f)
        refuse("control character");
      ++i;
      continue;
    }
    // Length of a UTF-8 sequence from its lead byte; continuation bytes
    // are 10xxxxxx. Overlong forms and surrogates are refused too.
    const std::size_t len = (c & 0xE0) == 0xC0   ? 2
                            : (c & 0xF0) == 0xE0 ? 3
                            : (c & 0xF8) == 0xF0 ? 4
                                                 : 0;
    if (len == 0 || c == 0xC0 || c == 0xC1 || c > 0xF4 || i + len > text.size())
      refuse("invalid UTF-8");
    std::uint32_t cp = c & (0x7F >> len);
    for (std::size_t k = 1; k < len; ++k) {
      const auto cc = static_cast<unsigned char>(text[i + k]);
      if ((cc & 0xC0) != 0x80) refuse("invalid UTF-8");
      cp = (cp << 6) | (cc & 0x3F);
    }
    if ((len == 3 && cp < 0x800) || (len == 4 && cp < 0x10000) || (cp >= 0xD800 && cp <= 0xDFFF) ||
        cp > 0x10FFFF)
      refuse("invalid UTF-8");
    i += len;
  }
}

// yaml-cpp 0.7 also loops for ever, allocating without bound, on some
// printable text (a lone "," is enough). The text is therefore parsed once
// in a forked child with a time and memory limit; only text that parses
// there is parsed here. A scene parses in milliseconds.
constexpr int kParseSeconds = 5;
constexpr rlim_t kParseMemoryBytes = rlim_t{1} << 30;
constexpr auto kParsePoll = std::chrono::milliseconds(1);

void check_parser_terminates(const std::string& text, const std::string& origin) {
  std::fflush(nullptr);  // or buffered output would be written twice
  const pid_t pid = ::fork();
  if (pid < 0) return;  // cannot isolate: parse directly, as before
  if (pid == 0) {
    const rlimit mem{kParseMemoryBytes, kParseMemoryBytes};
    ::setrlimit(RLIMIT_AS, &mem);
    int code = 0;
    try {
      (void)YAML::LoadAll(text);
    } catch (...) {
      code = 3;  // a parse error: the parent reports it with its message
    }
    std::_Exit(code);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kParseSeconds);
  int status = 0;
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) return;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      throw InputError(origin + ": malformed YAML: the parser did not finish within " +
                       std::to_string(kParseSeconds) +
                       " s (yaml-cpp loops on some malformed text; check the syntax)");
    }
    std::this_thread::sleep_for(kParsePoll);
  }
  if (WIFSIGNALED(status) ||
      (WIFEXITED(status) && WEXITSTATUS(status) != 0 && WEXITSTATUS(status) != 3))
    throw InputError(origin +
                     ": malformed YAML: the parser failed on this text (out of memory or crashed)");
}

}  // namespace

YAML::Node load_single_document(const std::string& text, const std::string& origin) {
  check_printable_utf8(text, origin);
  check_parser_terminates(text, origin);
  std::vector<YAML::Node> docs;
  try {
    docs = YAML::LoadAll(text);
  } catch (const YAML::Exception& e) {
    throw InputError(origin + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  }
  if (docs.size() > 1)
    throw InputError(at(origin, docs[1].Mark()) + ": expected one YAML document, found " +
                     std::to_string(docs.size()) + " (a second document starts here)");
  const YAML::Node root = docs.empty() ? YAML::Node() : docs.front();
  check_node(root, origin, "", 0);
  return root;
}

void check_yaml_text(const std::string& text, const std::string& origin) {
  (void)load_single_document(text, origin);
}

}  // namespace scene
