// hotmesh io: Figure rendering through Cairo (PNG and SVG surfaces).
#include "hotmesh/io/figure.hpp"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <numbers>

#include <fmt/format.h>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"

namespace hotmesh::io {
namespace {

constexpr double kMarginLeft = 80, kMarginRight = 30, kMarginTop = 50, kMarginBottom = 60;

/// World-to-pixel map with equal scales, centring the world window in the plot area.
struct Transform {
  double scale = 1, x0 = 0, y0 = 0, px0 = 0, py0 = 0;
  double px(double x) const { return px0 + (x - x0) * scale; }
  double py(double y) const { return py0 - (y - y0) * scale; }
};

/// Tick spacing of about `target` ticks over `span`: 1, 2 or 5 times a power of ten.
double nice_step(double span, int target) {
  const double raw = span / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= raw) return m * p;
  }
  return 10.0 * p;
}

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void set_color(cairo_t* cr, const Color& c) { cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a); }

}  // namespace

Color colormap(double value) {
  const double v = std::clamp(std::isfinite(value) ? value : 0.0, 0.0, 1.0);
  // Piecewise linear through blue, cyan, green, yellow, red.
  static constexpr std::array<Color, 5> stops{{{0.2, 0.3, 0.85}, {0.1, 0.75, 0.85}, {0.25, 0.75, 0.3},
                                                {0.95, 0.85, 0.15}, {0.85, 0.15, 0.1}}};
  const double s = v * (stops.size() - 1);
  const auto i = std::min<std::size_t>(static_cast<std::size_t>(s), stops.size() - 2);
  const double f = s - static_cast<double>(i);
  const Color& a = stops[i];
  const Color& b = stops[i + 1];
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}

Figure::Figure(FigureLayout layout) : layout_(std::move(layout)) {}

void Figure::polyline(std::span<const PlotPoint> points, Stroke stroke, bool closed) {
  commands_.push_back({Command::Kind::polyline, {points.begin(), points.end()}, stroke, {}, {}, 0, closed, {}});
}

void Figure::polygon(std::span<const PlotPoint> points, Color fill, std::optional<Stroke> edge) {
  commands_.push_back({Command::Kind::polygon, {points.begin(), points.end()}, {}, edge, fill, 0, true, {}});
}

void Figure::marker(PlotPoint at, Color color, double radius) {
  commands_.push_back({Command::Kind::marker, {at}, {}, {}, color, radius, false, {}});
}

void Figure::arrow(PlotPoint from, PlotPoint to, Stroke stroke, double head) {
  commands_.push_back({Command::Kind::arrow, {from, to}, stroke, {}, {}, head, false, {}});
}

void Figure::text(PlotPoint at, std::string label, double size, Color color, PlotPoint offset) {
  commands_.push_back({Command::Kind::text, {at}, {}, {}, color, size, false, std::move(label), offset});
}

void Figure::legend(std::string label, Stroke stroke, bool as_marker) {
  legend_.push_back({std::move(label), stroke, as_marker});
}

void Figure::color_bar(std::string label, double lo, double hi) { color_bar_ = ColorBar{std::move(label), lo, hi}; }

void Figure::set_view(double xmin, double xmax, double ymin, double ymax) { view_ = {xmin, xmax, ymin, ymax}; }

namespace {

struct Renderer {
  const FigureLayout& layout;
  Transform t;
  std::array<double, 4> view{};  // xmin, xmax, ymin, ymax

  void draw(cairo_t* cr, const Figure::Command& c) const {
    using Kind = Figure::Command::Kind;
    switch (c.kind) {
      case Kind::polyline:
      case Kind::polygon: {
        if (c.points.empty()) return;
        cairo_move_to(cr, t.px(c.points[0].x), t.py(c.points[0].y));
        for (std::size_t i = 1; i < c.points.size(); ++i) cairo_line_to(cr, t.px(c.points[i].x), t.py(c.points[i].y));
        if (c.closed) cairo_close_path(cr);
        if (c.kind == Kind::polygon) {
          set_color(cr, c.fill);
          if (c.edge) {
            cairo_fill_preserve(cr);
            set_color(cr, c.edge->color);
            cairo_set_line_width(cr, c.edge->width);
            cairo_stroke(cr);
          } else {
            cairo_fill(cr);
          }
        } else {
          set_color(cr, c.stroke.color);
          cairo_set_line_width(cr, c.stroke.width);
          cairo_stroke(cr);
        }
        return;
      }
      case Kind::marker:
        set_color(cr, c.fill);
        cairo_arc(cr, t.px(c.points[0].x), t.py(c.points[0].y), c.size, 0, 2 * std::numbers::pi);
        cairo_fill(cr);
        return;
      case Kind::arrow: {
        const double x0 = t.px(c.points[0].x), y0 = t.py(c.points[0].y);
        const double x1 = t.px(c.points[1].x), y1 = t.py(c.points[1].y);
        const double length = std::hypot(x1 - x0, y1 - y0);
        set_color(cr, c.stroke.color);
        cairo_set_line_width(cr, c.stroke.width);
        cairo_move_to(cr, x0, y0);
        cairo_line_to(cr, x1, y1);
        cairo_stroke(cr);
        if (length > 1e-9) {
          const double ux = (x1 - x0) / length, uy = (y1 - y0) / length;
          const double h = std::min(c.size, 0.5 * length);
          cairo_move_to(cr, x1, y1);
          cairo_line_to(cr, x1 - h * ux - 0.4 * h * uy, y1 - h * uy + 0.4 * h * ux);
          cairo_line_to(cr, x1 - h * ux + 0.4 * h * uy, y1 - h * uy - 0.4 * h * ux);
          cairo_close_path(cr);
          cairo_fill(cr);
        }
        return;
      }
      case Kind::text:
        set_color(cr, c.fill);
        cairo_set_font_size(cr, c.size);
        cairo_move_to(cr, t.px(c.points[0].x) + c.offset.x, t.py(c.points[0].y) - c.offset.y);
        cairo_show_text(cr, c.text.c_str());
        return;
    }
  }

  void draw_axes(cairo_t* cr) const {
    const double left = kMarginLeft, right = layout.width - kMarginRight;
    const double top = kMarginTop, bottom = layout.height - kMarginBottom;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, left, top, right - left, bottom - top);
    cairo_stroke(cr);
    cairo_set_font_size(cr, 12);
    const double xlo = view[0] + (left - t.px(view[0])) / t.scale, xhi = view[0] + (right - t.px(view[0])) / t.scale;
    const double ylo = view[2] + (t.py(view[2]) - bottom) / t.scale, yhi = view[2] + (t.py(view[2]) - top) / t.scale;
    const double dx = nice_step(xhi - xlo, 8), dy = nice_step(yhi - ylo, 6);
    for (double x = std::ceil(xlo / dx) * dx; x <= xhi + 1e-9 * dx; x += dx) {
      const double px = t.px(x);
      cairo_move_to(cr, px, bottom);
      cairo_line_to(cr, px, bottom + 5);
      cairo_stroke(cr);
      const std::string label = fmt::format("{:.6g}", std::abs(x) < 1e-12 * dx ? 0.0 : x);
      cairo_move_to(cr, px - 3.0 * static_cast<double>(label.size()), bottom + 19);
      cairo_show_text(cr, label.c_str());
    }
    for (double y = std::ceil(ylo / dy) * dy; y <= yhi + 1e-9 * dy; y += dy) {
      const double py = t.py(y);
      cairo_move_to(cr, left - 5, py);
      cairo_line_to(cr, left, py);
      cairo_stroke(cr);
      const std::string label = fmt::format("{:.6g}", std::abs(y) < 1e-12 * dy ? 0.0 : y);
      cairo_move_to(cr, left - 9 - 6.5 * static_cast<double>(label.size()), py + 4);
      cairo_show_text(cr, label.c_str());
    }
    cairo_set_font_size(cr, 14);
    cairo_move_to(cr, 0.5 * (left + right) - 4.0 * static_cast<double>(layout.x_label.size()), bottom + 45);
    cairo_show_text(cr, layout.x_label.c_str());
    cairo_save(cr);
    cairo_move_to(cr, 18, 0.5 * (top + bottom) + 4.0 * static_cast<double>(layout.y_label.size()));
    cairo_rotate(cr, -std::numbers::pi / 2);
    cairo_show_text(cr, layout.y_label.c_str());
    cairo_restore(cr);
  }
};

/// The world window that shows every point drawn, with a margin of 3 %.
std::array<double, 4> fitted_view(const std::vector<Figure::Command>& commands) {
  double inf = std::numeric_limits<double>::infinity();
  std::array<double, 4> view = {inf, -inf, inf, -inf};
  for (const auto& c : commands) {
    for (const auto& p : c.points) {
      view = {std::min(view[0], p.x), std::max(view[1], p.x), std::min(view[2], p.y), std::max(view[3], p.y)};
    }
  }
  if (!(view[0] <= view[1])) view = {0, 1, 0, 1};
  const double margin = 0.03 * std::max({view[1] - view[0], view[3] - view[2], 1e-300});
  return {view[0] - margin, view[1] + margin, view[2] - margin, view[3] + margin};
}

/// The legend in the top-right corner of the plot area (its right edge at `right`, top at
/// `top`), on a white box.
void draw_legend(cairo_t* cr, const std::vector<Figure::LegendEntry>& legend, double right, double top) {
  if (legend.empty()) return;
  const double row = 20, box_w = 260, x = right - box_w - 10, y = top + 10;
  cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
  cairo_rectangle(cr, x, y, box_w, row * static_cast<double>(legend.size()) + 10);
  cairo_fill(cr);
  cairo_set_font_size(cr, 13);
  for (std::size_t i = 0; i < legend.size(); ++i) {
    const auto& e = legend[i];
    const double cy = y + 15 + row * static_cast<double>(i);
    set_color(cr, e.stroke.color);
    if (e.as_marker) {
      cairo_arc(cr, x + 22, cy, 4, 0, 2 * std::numbers::pi);
      cairo_fill(cr);
    } else {
      cairo_set_line_width(cr, e.stroke.width);
      cairo_move_to(cr, x + 8, cy);
      cairo_line_to(cr, x + 36, cy);
      cairo_stroke(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_move_to(cr, x + 44, cy + 4);
    cairo_show_text(cr, e.label.c_str());
  }
}

/// The colour bar along the bottom edge, ending 30 pixels left of `right`.
void draw_color_bar(cairo_t* cr, const Figure::ColorBar& bar, double right, double height) {
  const double bx = right - 230, by = height - 22.0, bw = 200, bh = 12;
  for (int i = 0; i < 100; ++i) {
    set_color(cr, colormap((i + 0.5) / 100.0));
    cairo_rectangle(cr, bx + bw * i / 100.0, by, bw / 100.0 + 0.5, bh);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_font_size(cr, 12);
  const std::string text = fmt::format("{}  {:.3g}", bar.label, bar.lo);
  cairo_move_to(cr, bx - 7.0 * static_cast<double>(text.size()) - 4, by + 10);
  cairo_show_text(cr, text.c_str());
  const std::string hi = fmt::format("{:.3g}", bar.hi);
  cairo_move_to(cr, bx + bw + 4, by + 10);
  cairo_show_text(cr, hi.c_str());
}

}  // namespace

void Figure::save(const std::filesystem::path& path) const {
  const std::string ext = path.extension().string();
  if (ext != ".png" && ext != ".svg") throw InputError::in(path.string(), "pictures are written as .png or .svg");

  const std::array<double, 4> view = view_ ? *view_ : fitted_view(commands_);
  const double w = std::max(view[1] - view[0], 1e-300), h = std::max(view[3] - view[2], 1e-300);
  const double area_w = layout_.width - kMarginLeft - kMarginRight;
  const double area_h = layout_.height - kMarginTop - kMarginBottom;
  Renderer r{layout_, {}, view};
  r.t.scale = std::min(area_w / w, area_h / h);
  r.t.x0 = 0.5 * (view[0] + view[1]);
  r.t.y0 = 0.5 * (view[2] + view[3]);
  r.t.px0 = kMarginLeft + 0.5 * area_w;
  r.t.py0 = kMarginTop + 0.5 * area_h;

  std::string bytes;
  cairo_surface_t* surface =
      ext == ".svg" ? cairo_svg_surface_create_for_stream(append_to_string, &bytes, layout_.width, layout_.height)
                    : cairo_image_surface_create(CAIRO_FORMAT_ARGB32, layout_.width, layout_.height);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);

  cairo_save(cr);
  cairo_rectangle(cr, kMarginLeft, kMarginTop, area_w, area_h);
  cairo_clip(cr);
  for (const auto& c : commands_) r.draw(cr, c);
  cairo_restore(cr);
  if (layout_.axes) r.draw_axes(cr);

  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_font_size(cr, 18);
  cairo_move_to(cr, kMarginLeft, 30);
  cairo_show_text(cr, layout_.title.c_str());
  draw_legend(cr, legend_, kMarginLeft + area_w, kMarginTop);
  if (color_bar_) draw_color_bar(cr, *color_bar_, kMarginLeft + area_w, layout_.height);

  cairo_destroy(cr);
  if (ext == ".png") cairo_surface_write_to_png_stream(surface, append_to_string, &bytes);
  cairo_surface_finish(surface);
  const cairo_status_t status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (status == CAIRO_STATUS_NO_MEMORY) throw std::bad_alloc();  // the commands' out-of-memory exit, not bad input
  if (status != CAIRO_STATUS_SUCCESS) {
    throw InputError::in(path.string(), std::string("cannot render the picture: ") + cairo_status_to_string(status));
  }
  write_file_atomically(path, bytes);
}

}  // namespace hotmesh::io
