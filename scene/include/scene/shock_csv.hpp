#pragma once
// shock.csv, the file between shockfit (writes it) and meshgen (reads it):
// one row per station, a header row naming the columns. Readers find
// columns by name, so more columns may be present and in any order; only
// shock_x, shock_y and accepted are required. Lines starting with '#' are
// comments; fields may be surrounded by spaces or double quotes.
#include <cstddef>
#include <string>
#include <vector>

#include "scene/vec2.hpp"

namespace scene {

struct ShockCsvRow {
  int station = 0;  // the row's index when the column is absent
  // NaN where the file has no such column (or "nan" in it).
  Vec2 surface, normal, shock;
  double distance = 0.0;   // shock distance from the surface along the normal
  double ci = 0.0;         // 95% half-width of distance (scene units)
  double fit_error = 0.0;  // rms residual of the fit (field units)
  bool accepted = false;
};

struct ShockCsv {
  std::vector<ShockCsvRow> rows;  // every data row, in file order
  bool has_ci = false;            // the header has a ci column
};

// Accepted rows a shock curve needs: fewer leave no curve to cluster a grid at.
inline constexpr std::size_t kMinShockCurvePoints = 2;

// The columns shockfit writes, in order.
const std::vector<std::string>& shock_csv_columns();

// Writes every row under shock_csv_columns(), 12 significant digits,
// non-finite values as nan; atomically.
void write_shock_csv(const std::string& path, const std::vector<ShockCsvRow>& rows);

// Reads a shock.csv. InputError naming the file, the line and the column:
// missing or empty file, no header, a required column missing, a row too
// short for a column, a field that is not a number, accepted other than
// 0 or 1, an accepted row without a finite shock_x and shock_y, and fewer
// than kMinShockCurvePoints accepted rows.
ShockCsv read_shock_csv(const std::string& path);

}  // namespace scene
