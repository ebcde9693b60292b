#pragma once
// Report figures from lattice fields (gnuplot images with overlays).
#include <string>
#include <vector>

#include "scene/lattice.hpp"
#include "scene/vec2.hpp"

namespace pipeline {

struct Overlay {
  std::string title;
  std::vector<scene::Vec2> points;
  std::string style = "points pt 7 ps 0.6";
};

// Colour map of one lattice field with optional point/line overlays.
bool field_png(const scene::Lattice& lat, const std::string& field, const std::string& title,
               const std::vector<Overlay>& overlays, const std::string& png_path);

}  // namespace pipeline
