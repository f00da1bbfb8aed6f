#pragma once
// Private to rownav_render: the cairo recording behind a CairoCanvas (cairo_canvas.cpp draws
// into it, cairo_output.cpp replays it into PNG / SVG / PDF).
#include <cairo.h>

#include "rownav/io/cairo_canvas.hpp"

namespace rownav::io {

struct CairoCanvas::Recording {
  cairo_surface_t* surface = nullptr;
  cairo_t* cr = nullptr;
  int depth = 0;  // open groups (cairo_save without its restore)

  Recording(int width_px, int height_px) {
    const cairo_rectangle_t extents{0.0, 0.0, double(width_px), double(height_px)};
    surface = cairo_recording_surface_create(CAIRO_CONTENT_COLOR_ALPHA, &extents);
    cr = cairo_create(surface);
    // Unhinted metrics: text is laid out alike in the PNG, the SVG and the PDF, and its width
    // scales with the font size (hinted advances are whole pixels).
    cairo_font_options_t* options = cairo_font_options_create();
    cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
    cairo_font_options_set_hint_style(options, CAIRO_HINT_STYLE_SLIGHT);
    cairo_set_font_options(cr, options);
    cairo_font_options_destroy(options);
  }
  ~Recording() {
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
  }
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;
};

}  // namespace rownav::io
