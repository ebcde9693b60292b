#include "mutators.hpp"

#include <algorithm>
#include <sstream>

namespace fuzz {

namespace {

// Keys a scene may hold, mixed into mutations so that a value lands on a
// known key more often than a random one would.
const std::vector<std::string> kKeys = {"mach",
                                        "gamma",
                                        "angle_deg",
                                        "length",
                                        "radius",
                                        "diameter",
                                        "h_min",
                                        "h_max",
                                        "target_cells",
                                        "growth",
                                        "band_width",
                                        "particles",
                                        "packing_fraction",
                                        "restitution",
                                        "tc",
                                        "seed",
                                        "body_diameters",
                                        "lattice_nx",
                                        "lattice_ny",
                                        "warmup",
                                        "averaging",
                                        "replicas",
                                        "end_time",
                                        "write_interval",
                                        "np",
                                        "levels",
                                        "stations",
                                        "bootstrap",
                                        "window",
                                        "xmin",
                                        "xmax",
                                        "ymin",
                                        "ymax",
                                        "gravity",
                                        "collisions",
                                        "time",
                                        "smoothing",
                                        "curve_tolerance",
                                        "inflow_packing_fraction",
                                        "min_samples",
                                        "noise_factor",
                                        "h_body",
                                        "h_uniform",
                                        "anisotropy"};
const std::vector<std::string> kSections = {"body",     "freestream", "granular", "mesh", "cfd",
                                            "shockfit", "pipeline",   "domain",   "box"};

std::size_t pick(Rng& rng, std::size_t n) {
  return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream is(text);
  for (std::string l; std::getline(is, l);) out.push_back(l);
  return out;
}

std::string join(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

std::string junk(Rng& rng, std::size_t n) {
  std::string s(n, '\0');
  for (char& c : s) c = static_cast<char>(pick(rng, 256));
  return s;
}

// Replaces the value after "key:" on a line that has one.
bool replace_value(std::vector<std::string>& lines, Rng& rng, const std::string& value) {
  std::vector<std::size_t> with_value;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto c = lines[i].find(':');
    if (c != std::string::npos && c + 1 < lines[i].size() &&
        lines[i].find_first_not_of(" ", c + 1) != std::string::npos && lines[i][0] != '#')
      with_value.push_back(i);
  }
  if (with_value.empty()) return false;
  std::string& l = lines[with_value[pick(rng, with_value.size())]];
  l = l.substr(0, l.find(':') + 1) + " " + value;
  return true;
}

}  // namespace

std::string hostile_value(Rng& rng) {
  static const std::vector<std::string> kValues = {".nan",
                                                   ".NaN",
                                                   "nan",
                                                   ".inf",
                                                   "-.inf",
                                                   "inf",
                                                   "1e308",
                                                   "-1e308",
                                                   "1e-308",
                                                   "4.9e-324",
                                                   "0",
                                                   "-0",
                                                   "-1",
                                                   "-1e-9",
                                                   "1e-300",
                                                   "9223372036854775807",
                                                   "9223372036854775808",
                                                   "18446744073709551616",
                                                   "-9223372036854775809",
                                                   "1e19",
                                                   "2147483648",
                                                   "0x7fffffff",
                                                   "1.0000000000000002",
                                                   "0.9999999999999999",
                                                   "1",
                                                   "1e6",
                                                   "1e9",
                                                   "1e12",
                                                   "\"3\"",
                                                   "three",
                                                   "true",
                                                   "null",
                                                   "~",
                                                   "[]",
                                                   "{}",
                                                   "[1, 2]",
                                                   "{a: 1}",
                                                   "''",
                                                   "!!binary AAAA",
                                                   "*anchor",
                                                   "&a 1",
                                                   "\"\\u0000\"",
                                                   "1_000",
                                                   "+.inf",
                                                   "0.5",
                                                   "1e-12",
                                                   "100000000000"};
  return kValues[pick(rng, kValues.size())];
}

std::string hostile_name(Rng& rng, const std::string& ext) {
  static const std::vector<std::string> kNames = {"with space",
                                                  "quote'in",
                                                  "dq\"in",
                                                  "\xc3\xbc"
                                                  "n"
                                                  "\xc3\xaf"
                                                  "c"
                                                  "\xc3\xb6"
                                                  "de",
                                                  "-leading-dash",
                                                  "semi;colon",
                                                  "dollar$HOME",
                                                  "star*",
                                                  "back\\slash",
                                                  "tab\tin",
                                                  "percent%s%n",
                                                  std::string(180, 'x'),
                                                  "new\nline",
                                                  ".hidden",
                                                  "--help"};
  return kNames[pick(rng, kNames.size())] + ext;
}

std::string mutate_scene(const std::string& text, Rng& rng, std::string& kind) {
  std::vector<std::string> lines = lines_of(text);
  switch (pick(rng, 16)) {
    case 0:
    case 1:
    case 2:
      kind = "value";
      if (replace_value(lines, rng, hostile_value(rng))) return join(lines);
      [[fallthrough]];
    case 3: {
      kind = "extra-key";
      const std::string sec = kSections[pick(rng, kSections.size())];
      const std::string key = kKeys[pick(rng, kKeys.size())];
      return text + sec + ":\n  " + key + ": " + hostile_value(rng) + "\n";
    }
    case 4: {
      kind = "duplicate-line";
      if (lines.empty()) return text;
      const std::size_t i = pick(rng, lines.size());
      lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i), lines[i]);
      return join(lines);
    }
    case 5:
      kind = "truncate";
      return text.substr(0, pick(rng, text.size() + 1));
    case 6: {
      kind = "junk";
      std::string t = text;
      const std::size_t at = pick(rng, t.size() + 1);
      return t.insert(at, junk(rng, 1 + pick(rng, 64)));
    }
    case 7: {
      // Binary junk, or printable YAML punctuation soup (which made yaml-cpp
      // loop for ever).
      if (pick(rng, 2)) {
        kind = "all-junk";
        return junk(rng, pick(rng, 4096));
      }
      kind = "printable-junk";
      static const std::string kAlphabet = "abc:{}[],-?&*!|>'\"%@`#\n \t0123456789.e+";
      std::string t(pick(rng, 2048), ' ');
      for (char& c : t) c = kAlphabet[pick(rng, kAlphabet.size())];
      return t;
    }
    case 8:
      kind = "second-document";
      return text + "---\n" + text;
    case 9:
      kind = "complex-key";
      return text + (pick(rng, 2) ? "? [a, b]\n: 1\n" : "{x: 1}: 2\n");
    case 10: {
      kind = "delete-line";
      if (lines.empty()) return text;
      lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(pick(rng, lines.size())));
      return join(lines);
    }
    case 11: {
      kind = "deep";
      const std::size_t depth = 10 + pick(rng, 5000);
      return text + "granular:\n  gravity: " + std::string(depth, '[') + std::string(depth, ']') +
             "\n";
    }
    case 12: {
      kind = "mesh-size";
      return text + "mesh:\n  h_min: " + hostile_value(rng) + "\n  h_max: " + hostile_value(rng) +
             "\n";
    }
    case 13: {
      kind = "subsonic";
      return text + "freestream:\n  mach: " +
             std::to_string(0.1 + 0.9 * std::uniform_real_distribution<double>()(rng)) + "\n";
    }
    case 14: {
      kind = "name";
      return "name: " + hostile_value(rng) + "\n" + text;
    }
    default: {
      kind = "two-values";
      replace_value(lines, rng, hostile_value(rng));
      replace_value(lines, rng, hostile_value(rng));
      return join(lines);
    }
  }
}

std::string mutate_vti(const std::string& text, Rng& rng, std::string& kind) {
  std::string t = text;
  auto replace_first = [&](const std::string& from, const std::string& to) {
    const auto at = t.find(from);
    if (at != std::string::npos) t.replace(at, from.size(), to);
  };
  switch (pick(rng, 10)) {
    case 0:
      kind = "vti-truncate";
      return t.substr(0, pick(rng, t.size() + 1));
    case 1: {
      kind = "vti-all-nan";
      std::string out;
      bool in_data = false;
      std::istringstream is(t);
      for (std::string l; std::getline(is, l);) {
        if (l.find("</DataArray") != std::string::npos) in_data = false;
        out += (in_data ? std::string("nan nan nan nan nan nan nan nan nan nan") : l) + "\n";
        if (l.find("<DataArray") != std::string::npos) in_data = true;
      }
      return out;
    }
    case 2:
      kind = "vti-extent";
      replace_first(
          "WholeExtent=\"0 ",
          "WholeExtent=\"0 " + std::string(pick(rng, 2) ? "99999999" : "4294967296") + "0");
      return t;
    case 3:
      kind = "vti-spacing";
      replace_first("Spacing=\"", "Spacing=\"" + std::string(pick(rng, 2) ? "nan" : "-"));
      return t;
    case 4:
      kind = "vti-origin";
      replace_first("Origin=\"", "Origin=\"inf");
      return t;
    case 5:
      kind = "vti-junk";
      return t.insert(pick(rng, t.size() + 1), junk(rng, 1 + pick(rng, 256)));
    case 6:
      kind = "vti-no-close";
      replace_first("</DataArray>", "");
      return t;
    case 7:
      kind = "vti-bad-number";
      replace_first("format=\"ascii\">\n", "format=\"ascii\">\n1e999 zz ");
      return t;
    case 8:
      kind = "vti-empty";
      return "";
    default:
      kind = "vti-all-junk";
      return junk(rng, pick(rng, 8192));
  }
}

std::string mutate_csv(const std::string& text, Rng& rng, std::string& kind) {
  std::vector<std::string> lines = lines_of(text);
  switch (pick(rng, 7)) {
    case 0:
      kind = "csv-truncate";
      return text.substr(0, pick(rng, text.size() + 1));
    case 1:
      kind = "csv-value";
      if (lines.size() > 1) {
        std::string& l = lines[1 + pick(rng, lines.size() - 1)];
        const auto comma = l.find(',');
        l = hostile_value(rng) + (comma == std::string::npos ? "" : l.substr(comma));
      }
      return join(lines);
    case 2:
      kind = "csv-header";
      if (!lines.empty()) lines[0] = "x,y,z";
      return join(lines);
    case 3:
      kind = "csv-junk";
      return junk(rng, pick(rng, 2048));
    case 4:
      kind = "csv-none-accepted";
      for (std::size_t i = 1; i < lines.size(); ++i) {
        const auto c = lines[i].find(",1");
        if (c != std::string::npos) lines[i].replace(c, 2, ",0");
      }
      return join(lines);
    case 5:
      kind = "csv-short-row";
      lines.push_back("1.0");
      return join(lines);
    default:
      kind = "csv-far-away";
      lines.push_back("1e300,-1e300,1,0.01");
      return join(lines);
  }
}

}  // namespace fuzz
