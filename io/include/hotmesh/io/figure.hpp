// hotmesh io: pictures for people (PNG) and for pages (SVG). A Figure records 2D drawing
// commands in world coordinates and renders them through Cairo when saved, fitted to the
// picture with equal scales on both axes; the same figure can be saved in both formats.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace hotmesh::io {

struct PlotPoint {
  double x = 0.0;
  double y = 0.0;
};

struct Color {
  double r = 0.0, g = 0.0, b = 0.0, a = 1.0;
};

namespace colors {
inline constexpr Color black{0, 0, 0};
inline constexpr Color grey{0.55, 0.55, 0.55};
inline constexpr Color blue{0.12, 0.35, 0.75};
inline constexpr Color red{0.82, 0.15, 0.12};
inline constexpr Color green{0.15, 0.6, 0.25};
inline constexpr Color orange{0.95, 0.55, 0.1};
}  // namespace colors

/// Blue (0) - green - yellow - red (1) for a value in [0, 1]; values outside are clamped.
Color colormap(double value);

struct Stroke {
  Color color = colors::black;
  double width = 1.0;  ///< in pixels
};

/// The world window and what is around the drawing.
struct FigureLayout {
  int width = 1200;   ///< pixels
  int height = 800;
  std::string title;
  std::string x_label;
  std::string y_label;
  bool axes = true;   ///< a frame with tick labels in world units
};

class Figure {
 public:
  explicit Figure(FigureLayout layout = {});

  void polyline(std::span<const PlotPoint> points, Stroke stroke, bool closed = false);
  void polygon(std::span<const PlotPoint> points, Color fill, std::optional<Stroke> edge = std::nullopt);
  void marker(PlotPoint at, Color color, double radius = 3.0);
  /// An arrow from `from` to `to` in world coordinates; head size in pixels.
  void arrow(PlotPoint from, PlotPoint to, Stroke stroke, double head = 8.0);
  /// Text anchored at a world position (left-baseline), size in pixels, moved from there by
  /// `offset` pixels (right, up): labels at a fixed distance from what they label at any zoom.
  void text(PlotPoint at, std::string text, double size = 14.0, Color color = colors::black, PlotPoint offset = {});
  /// A legend line: a short stroke or marker sample and its label.
  void legend(std::string label, Stroke stroke, bool as_marker = false);
  /// A colour bar for values [lo, hi] drawn with colormap().
  void color_bar(std::string label, double lo, double hi);

  /// The world window to show; without it the figure shows everything drawn, with a margin.
  void set_view(double xmin, double xmax, double ymin, double ymax);

  /// Renders to .png or .svg by extension, atomically. Throws hotmesh::InputError for other
  /// extensions or if the file cannot be written.
  void save(const std::filesystem::path& path) const;

  /// One recorded drawing command.
  struct Command {
    enum class Kind { polyline, polygon, marker, arrow, text } kind = Kind::polyline;
    std::vector<PlotPoint> points;
    Stroke stroke;
    std::optional<Stroke> edge;
    Color fill;
    double size = 0.0;  ///< marker radius, arrow head or text size, in pixels
    bool closed = false;
    std::string text;
    PlotPoint offset;  ///< text only: pixels right and up from the anchor
  };

  /// One line of the legend.
  struct LegendEntry {
    std::string label;
    Stroke stroke;
    bool as_marker;
  };
  /// The colour bar's label and range.
  struct ColorBar {
    std::string label;
    double lo, hi;
  };

 private:
  FigureLayout layout_;
  std::vector<Command> commands_;
  std::vector<LegendEntry> legend_;
  std::optional<ColorBar> color_bar_;
  std::optional<std::array<double, 4>> view_;
};

}  // namespace hotmesh::io
