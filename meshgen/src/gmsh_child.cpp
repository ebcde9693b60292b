#include "gmsh_child.hpp"

#include <gmsh.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>

#include "scene/cli.hpp"
#include "scene/errors.hpp"

namespace meshgen {

namespace {

// How often the parent looks for the child's exit and for Ctrl-C: well
// under the second a user waits after pressing it.
constexpr auto kPoll = std::chrono::milliseconds(20);
// Child exit codes: 0 result written; these carry an error message instead.
constexpr int kChildInputError = 3;
constexpr int kChildRunError = 4;

template <class T>
void put(std::ostream& os, const T& v) {
  os.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
bool get(std::istream& is, T& v) {
  return static_cast<bool>(is.read(reinterpret_cast<char*>(&v), sizeof v));
}

void write_mesh(const PlaneMesh& m, const std::string& path) {
  std::ofstream os(path, std::ios::binary);
  put(os, static_cast<std::uint64_t>(m.nodes.size()));
  for (const scene::Vec2 p : m.nodes) {
    put(os, p.x);
    put(os, p.y);
  }
  put(os, static_cast<std::uint64_t>(m.cells.size()));
  for (const auto& c : m.cells) put(os, c);
  put(os, static_cast<std::uint64_t>(m.boundary.size()));
  for (const BoundaryEdge& e : m.boundary) {
    put(os, e.a);
    put(os, e.b);
    put(os, static_cast<int>(e.patch));
  }
  put(os, m.quads);
  put(os, m.triangles);
  put(os, m.pieces);
  if (!os.flush()) throw scene::RunError(path + ": cannot write the gmsh result");
}

PlaneMesh read_mesh(const std::string& path) {
  std::ifstream is(path, std::ios::binary);
  PlaneMesh m;
  std::uint64_t n = 0;
  bool ok = get(is, n);
  for (std::uint64_t i = 0; ok && i < n; ++i) {
    scene::Vec2 p;
    ok = get(is, p.x) && get(is, p.y);
    m.nodes.push_back(p);
  }
  ok = ok && get(is, n);
  for (std::uint64_t i = 0; ok && i < n; ++i) {
    std::array<int, 4> c{};
    ok = get(is, c);
    m.cells.push_back(c);
  }
  ok = ok && get(is, n);
  for (std::uint64_t i = 0; ok && i < n; ++i) {
    BoundaryEdge e;
    int patch = 0;
    ok = get(is, e.a) && get(is, e.b) && get(is, patch);
    e.patch = static_cast<Patch>(patch);
    m.boundary.push_back(e);
  }
  ok = ok && get(is, m.quads) && get(is, m.triangles) && get(is, m.pieces);
  if (!ok) throw scene::RunError(path + ": truncated gmsh result from the meshing process");
  return m;
}

// The child's scratch file, for the terminate handler (which takes no
// arguments): set once, in the child only.
const std::string*& child_scratch() {
  static const std::string* path = nullptr;
  return path;
}

// gmsh reports some errors by throwing from inside its OpenMP regions, where
// no handler can catch them and the process terminates. Its last logged
// error then becomes the child's message instead of a bare "crashed".
[[noreturn]] void on_terminate() {
  std::string last;
  gmsh::logger::getLastError(last);
  if (child_scratch() != nullptr)
    std::ofstream(*child_scratch()) << "gmsh failed: " << (last.empty() ? "aborted" : last);
  std::_Exit(kChildRunError);
}

[[noreturn]] void child(const std::function<PlaneMesh()>& mesh, const std::string& scratch) {
  // The parent decides about Ctrl-C (it kills this process); a terminal's
  // SIGINT reaches the whole process group, so ignore it here.
  std::signal(SIGINT, SIG_IGN);
  child_scratch() = &scratch;
  std::set_terminate(on_terminate);
  int code = 0;
  try {
    write_mesh(mesh(), scratch);
  } catch (const scene::InputError& e) {
    std::ofstream(scratch) << e.what();
    code = kChildInputError;
  } catch (const std::exception& e) {
    std::ofstream(scratch) << e.what();
    code = kChildRunError;
  } catch (...) {
    std::ofstream(scratch) << "gmsh failed with an unknown exception";
    code = kChildRunError;
  }
  // _exit: no atexit handlers or static destructors of the parent's copy.
  std::_Exit(code);
}

std::string slurp(const std::string& path) {
  std::ifstream is(path);
  std::ostringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

PlaneMesh mesh_in_child(const std::function<PlaneMesh()>& mesh, const std::string& scratch_file) {
  std::fflush(nullptr);  // or buffered output would be written twice
  const pid_t pid = ::fork();
  if (pid < 0)
    throw scene::RunError(std::string("cannot start the meshing process: ") + std::strerror(errno));
  if (pid == 0) child(mesh, scratch_file);

  struct Scratch {  // removed however this function ends
    std::string path;
    ~Scratch() {
      std::error_code ec;
      std::filesystem::remove(path, ec);
    }
  } const scratch{scratch_file};
  int status = 0;
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR)
      throw scene::RunError("lost the meshing process: " + std::string(std::strerror(errno)));
    if (scene::interrupted()) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      throw scene::RunError("interrupted while gmsh was meshing");
    }
    std::this_thread::sleep_for(kPoll);
  }
  if (WIFSIGNALED(status))
    throw scene::RunError("gmsh crashed (signal " + std::to_string(WTERMSIG(status)) + ", " +
                          strsignal(WTERMSIG(status)) + ")");
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == kChildInputError) throw scene::InputError(slurp(scratch_file));
  if (code != 0) {
    const std::string msg = slurp(scratch_file);
    throw scene::RunError(msg.empty() ? "gmsh process exited with code " + std::to_string(code)
                                      : msg);
  }
  return read_mesh(scratch_file);
}

}  // namespace

PlaneMesh mesh_with_gmsh_in_child(const FluidRegion& region, const SizeField& size,
                                  const GmshJob& job, const std::string& scratch_file) {
  return mesh_in_child([&] { return mesh_with_gmsh(region, size, job); }, scratch_file);
}

PlaneMesh mesh_with_gmsh_in_child(const FluidRegion& region, const SizeFunction& size,
                                  const std::vector<ShockStrip>& strips, const GmshJob& job,
                                  const std::string& scratch_file) {
  return mesh_in_child([&] { return mesh_with_gmsh(region, size, strips, job); }, scratch_file);
}

}  // namespace meshgen
