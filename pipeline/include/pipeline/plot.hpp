#pragma once
// PNG figures through gnuplot (pngcairo). Plotting never fails a run: a
// missing gnuplot or a plotting error is reported on stderr and skipped.
#include <string>
#include <vector>

namespace pipeline {

struct Series {
  std::string title;
  std::vector<double> x, y;
  std::vector<double> yerr;           // optional error bars (same length as y)
  std::string style = "linespoints";  // gnuplot "with" clause (yerrorlines when yerr is given)
};

struct PlotSpec {
  std::string title, xlabel, ylabel;
  bool logx = false, logy = false;
  std::vector<Series> series;
  std::vector<std::string> extra;  // raw gnuplot lines (arrows, labels, hlines)
  int width = 900, height = 600;
};

// Returns true when the PNG was written.
bool plot_png(const PlotSpec& spec, const std::string& png_path);
// Runs a raw gnuplot script (for image plots); true on success.
bool run_gnuplot(const std::string& script, const std::string& work_dir);

}  // namespace pipeline
