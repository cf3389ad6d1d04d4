#include "sim/study/study_plane.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "sim/study/study_conclusions.hpp"

namespace vmt::sim::study {
namespace {

std::string Num(double v, const char* fmt = "%.1f") {
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, v + 0.0);
  return buf;
}

std::string Str(const CaseResult& r, const char* key) {
  return r.contains(key) && r[key].is_string() ? r[key].get<std::string>() : "";
}

struct Box {
  double z0 = std::numeric_limits<double>::infinity(), z1 = -z0, x0 = z0, x1 = -z0;
  void Add(double x, double z) {
    x0 = std::min(x0, x), x1 = std::max(x1, x), z0 = std::min(z0, z), z1 = std::max(z1, z);
  }
};

bool IsPoint(const nlohmann::ordered_json& p) {
  return p.is_array() && p.size() == 3 && p[0].is_number() && p[1].is_number() && p[2].is_number();
}

}  // namespace

std::string Esc(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<')
      o += "&lt;";
    else if (c == '>')
      o += "&gt;";
    else if (c == '&')
      o += "&amp;";
    else if (c == '"')
      o += "&quot;";
    else
      o += c;
  }
  return o;
}

const char* ClassColour(const std::string& cls) {
  if (cls == "clear") return "#2a9d3f";
  if (cls == "crash") return "#d62828";
  if (cls == "graze") return "#7b2cbf";
  if (cls == "retract_refused") return "#6c757d";
  return "#f08c00";
}

double TickStep(double span, int ticks) {
  const double raw = std::max(span, 1e-9) / std::max(ticks, 1);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

std::string PlaneSvg(const std::vector<const CaseResult*>& cases, const Reference* ref,
                     std::string (*href)(const std::string& case_id)) {
  Box box;
  if (ref)
    for (const auto& [x, z] : ref->path) box.Add(x, z);
  for (const CaseResult* r : cases) {
    for (const auto& p : Field(*r, "path")) box.Add(p[0].get<double>(), p[1].get<double>());
    if (ref && ref->has_tip && IsPoint(Field(*r, "point"))) {
      const auto& p = Field(*r, "point");
      box.Add(std::hypot(p[0].get<double>(), p[1].get<double>()) - ref->tip_x,
              p[2].get<double>() - ref->tip_z);
    }
  }
  if (!std::isfinite(box.x0)) return "<p>(no paths)</p>\n";
  // Room around the paths for the chuck's parts nearby (drawn as far as they reach into it).
  const double margin = 0.08 * std::max(box.z1 - box.z0, box.x1 - box.x0);
  box.Add(box.x0 - margin, box.z0 - margin), box.Add(box.x1 + margin, box.z1 + margin);
  const double w = 680, h = 460, left = 50, right = 15, top = 15, bottom = 35;
  const double span_z = std::max(box.z1 - box.z0, 1.0), span_x = std::max(box.x1 - box.x0, 1.0);
  const double s = std::min((w - left - right) / span_z, (h - top - bottom) / span_x);
  auto px = [&](double z) { return Num(left + (z - box.z0) * s); };
  auto py = [&](double x) { return Num(h - bottom - (x - box.x0) * s); };
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h
    << "\" style=\"border:1px solid #ccc;background:#fff\" font-family=\"sans-serif\">\n";
  // The scale: ticks every 1, 2 or 5 x 10^n mm on both axes.
  const double zs = TickStep(span_z, 8), xs = TickStep(span_x, 6);
  o << "<g stroke=\"#eee\" font-size=\"10\" fill=\"#555\">\n";
  for (double z = std::ceil(box.z0 / zs) * zs; z <= box.z1 + 1e-9; z += zs)
    o << "<line x1=\"" << px(z) << "\" y1=\"" << top << "\" x2=\"" << px(z) << "\" y2=\""
      << h - bottom << "\"/><text stroke=\"none\" text-anchor=\"middle\" x=\"" << px(z) << "\" y=\""
      << h - bottom + 13 << "\">" << Num(z, "%g") << "</text>\n";
  for (double x = std::ceil(box.x0 / xs) * xs; x <= box.x1 + 1e-9; x += xs)
    o << "<line x1=\"" << left << "\" y1=\"" << py(x) << "\" x2=\"" << w - right << "\" y2=\""
      << py(x) << "\"/><text stroke=\"none\" text-anchor=\"end\" x=\"" << left - 4 << "\" y=\""
      << py(x) << "\" dy=\"3\">" << Num(x, "%g") << "</text>\n";
  o << "</g>\n<text x=\"" << w - right - 150 << "\" y=\"" << h - 4
    << "\" font-size=\"11\">Z, mm (machine) &#8594;</text><text x=\"4\" y=\"11\" "
       "font-size=\"11\">X, mm (machine) &#8593;</text>\n";
  // An inner viewport of the plotting area clips the chuck's parts to it.
  o << "<svg x=\"" << left << "\" y=\"" << top << "\" width=\"" << Num(w - left - right)
    << "\" height=\"" << Num(h - top - bottom) << "\" viewBox=\"" << left << " " << top << " "
    << Num(w - left - right) << " " << Num(h - top - bottom) << "\" overflow=\"hidden\">\n";
  if (ref)
    for (const ChuckOutline& c : ref->chuck) {
      const double x1 = std::max(c.x1, 0.0);
      o << "<rect fill=\"#adb5bd\" fill-opacity=\"0.15\" stroke=\"#495057\" stroke-width=\"1\" "
           "stroke-dasharray=\"4 2\" x=\""
        << px(c.z0) << "\" y=\"" << py(x1) << "\" width=\"" << Num((c.z1 - c.z0) * s)
        << "\" height=\"" << Num((x1 - box.x0) * s) << "\"><title>" << Esc(c.name)
        << ": what it sweeps while the spindle turns, X up to " << Num(x1, "%.1f") << " mm, Z "
        << Num(c.z0, "%.1f") << " to " << Num(c.z1, "%.1f") << " mm</title></rect>\n";
    }
  o << "</svg>\n";
  if (ref && !ref->path.empty()) {
    o << "<polyline fill=\"none\" stroke=\"#888\" stroke-width=\"1.5\" points=\"";
    for (const auto& [x, z] : ref->path) o << px(z) << "," << py(x) << " ";
    o << "\"><title>the program's tool path (reference run)</title></polyline>\n";
  }
  // Clear first, so that failures are drawn on top, crashes last.
  for (const char* pass : {"clear", "error", "graze", "crash"})
    for (const CaseResult* r : cases) {
      const std::string cls = ClassOf(*r);
      if (cls != pass) continue;
      const auto& path = Field(*r, "path");
      if (path.empty()) continue;
      const std::string id = Str(*r, "case");
      o << "<a href=\"" << Esc(href(id)) << "\">";
      o << "<polyline fill=\"none\" stroke-opacity=\"0.6\" stroke=\"" << ClassColour(cls)
        << "\" stroke-width=\"1\" points=\"";
      for (const auto& p : path)
        o << px(p[1].get<double>()) << "," << py(p[0].get<double>()) << " ";
      o << "\"><title>" << Esc(id) << ": " << Esc(cls) << "</title></polyline></a>\n";
      if (cls != "crash" && cls != "graze") continue;
      const std::string parts = Field(*r, "parts").is_array() ? Field(*r, "parts").dump() : "";
      const auto& last = path.back();
      o << "<circle r=\"3\" fill=\"" << ClassColour(cls) << "\" cx=\"" << px(last[1].get<double>())
        << "\" cy=\"" << py(last[0].get<double>()) << "\"><title>" << Esc(id) << ": " << Esc(cls)
        << ", the axes at the first contact " << Esc(ContactAxes(*r)) << ", " << Esc(parts)
        << "</title></circle>\n";
      // The contact point itself, where the tool tip would touch it.
      if (ref && ref->has_tip && IsPoint(Field(*r, "point"))) {
        const auto& p = Field(*r, "point");
        const double cx = std::hypot(p[0].get<double>(), p[1].get<double>()) - ref->tip_x;
        const double cz = p[2].get<double>() - ref->tip_z;
        const std::string X = px(cz), Y = py(cx);
        o << "<path stroke=\"" << ClassColour(cls) << "\" stroke-width=\"1.5\" d=\"M" << X << " "
          << Y << "m-4 -4l8 8m-8 0l8 -8\"><title>" << Esc(id) << ": the contact point X"
          << Num(cx, "%.3f") << " Z" << Num(cz, "%.3f") << " " << Esc(parts) << "</title></path>\n";
      }
    }
  o << "</svg>\n";
  return o.str();
}

}  // namespace vmt::sim::study
