#include "scene/gnuplot.hpp"

#include <filesystem>
#include <fstream>

#include "scene/errors.hpp"

namespace scene {

namespace {

// ASCII DEL: a control character too.
constexpr unsigned char kDelete = 0x7f;

std::string last_line(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  return last;
}

}  // namespace

std::string gnuplot_string(std::string_view text) {
  std::string out = "'";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\'')
      out += "''";
    else if (u < ' ' || u == kDelete)
      out += ' ';
    else
      out += c;
  }
  return out + "'";
}

std::string gnuplot_path(std::string_view path) {
  if (!path.empty() && path.front() == '/') return gnuplot_string(path);
  return gnuplot_string("./" + std::string(path));
}

ChildTimes run_gnuplot(const std::string& script_path, const std::string& work_dir,
                       const std::string& log_path) {
  namespace fs = std::filesystem;
  // Absolute, so that the child's working directory does not change what the
  // path names, and a name starting with '-' is never read as an option.
  const std::string script = fs::absolute(script_path).string();
  ChildProcess gnuplot({"gnuplot", script}, ChildOptions{work_dir, log_path});
  const int rc = gnuplot.wait();
  if (rc != 0)
    throw RunError("gnuplot failed (exit " + std::to_string(rc) + "), see " + log_path + ": " +
                   last_line(log_path));
  return gnuplot.times();
}

}  // namespace scene
