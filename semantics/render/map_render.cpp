// The map drawn with VTK off-screen: boxes in class colours with dark edges and class labels, the
// trajectory, the map points, a metre grid under everything, a legend of counts by class.
#include "semantics/render/map_render.h"

#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkBillboardTextActor3D.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty2D.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>

#include "slam/io/text_file.h"

namespace wardmap::semantics {

namespace {

namespace fs = std::filesystem;

// How the picture looks. Colours RGB 0-1.
struct RenderStyle {
  std::array<double, 3> background{1.0, 1.0, 1.0};
  std::array<double, 3> grid{0.82, 0.82, 0.82};
  std::array<double, 3> text{0.12, 0.12, 0.12};
  double edge_darkening = 0.45;     // box edges: the class colour times this
  double ambient = 0.3, diffuse = 0.7;  // a face turned to the camera shows its exact class colour
  double edge_width = 2.0, trajectory_width = 2.5, point_size = 2.0;
  double fill = 0.88;               // share of the picture the map's objects and trajectory fill
  double oblique_elevation_deg = 50, oblique_azimuth_deg = 25, oblique_view_angle_deg = 30;
  int grid_lines = 16;              // about this many grid lines across the map (1-2-5 steps)
};
const RenderStyle kStyle;

using Box3 = Eigen::AlignedBox3d;

Eigen::Vector3d transform(const Eigen::Matrix4d& M, const Eigen::Vector3d& p) { return (M * p.homogeneous()).head<3>(); }

Box3 local_bounds(const SceneObject& o) {
  Box3 b;
  for (const auto& v : o.vertices) b.extend(v.cast<double>());
  return b;
}

std::array<Eigen::Vector3d, 8> corners(const Box3& b) {
  std::array<Eigen::Vector3d, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = Eigen::Vector3d(i & 1 ? b.max().x() : b.min().x(), i & 2 ? b.max().y() : b.min().y(),
                           i & 4 ? b.max().z() : b.min().z());
  return c;
}

Box3 world_bounds(const SceneObject& o) {
  Box3 w;
  const Box3 l = local_bounds(o);
  if (l.isEmpty()) return w;
  for (const auto& c : corners(l)) w.extend(transform(o.world, c));
  return w;
}

vtkSmartPointer<vtkMatrix4x4> vtk_matrix(const Eigen::Matrix4d& M) {
  auto m = vtkSmartPointer<vtkMatrix4x4>::New();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m->SetElement(r, c, M(r, c));
  return m;
}

vtkSmartPointer<vtkActor> actor_for(vtkPolyData* data) {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

// The object's mesh, and its 12 box edges (the mesh's own bounds, so oriented with the object).
void add_object(vtkRenderer* ren, const SceneObject& o) {
  if (o.vertices.empty()) return;
  const auto M = vtk_matrix(o.world);
  const Eigen::Vector3d rgb = o.colour.head<3>().cast<double>();

  vtkNew<vtkPoints> pts;
  for (const auto& v : o.vertices) pts->InsertNextPoint(v.x(), v.y(), v.z());
  vtkNew<vtkCellArray> tris;
  for (size_t i = 0; i + 2 < o.triangles.size(); i += 3) {
    const vtkIdType ids[3] = {o.triangles[i], o.triangles[i + 1], o.triangles[i + 2]};
    tris->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(pts);
  mesh->SetPolys(tris);
  auto surface = actor_for(mesh);
  surface->SetUserMatrix(M);
  surface->GetProperty()->SetColor(rgb.x(), rgb.y(), rgb.z());
  surface->GetProperty()->SetAmbient(kStyle.ambient);
  surface->GetProperty()->SetDiffuse(kStyle.diffuse);
  surface->GetProperty()->SetSpecular(0.0);
  surface->GetProperty()->SetOpacity(std::clamp(static_cast<double>(o.colour.w()), 0.05, 1.0));
  ren->AddActor(surface);

  const auto c = corners(local_bounds(o));
  vtkNew<vtkPoints> cp;
  for (const auto& p : c) cp->InsertNextPoint(p.x(), p.y(), p.z());
  vtkNew<vtkCellArray> edges;
  for (int i = 0; i < 8; ++i)
    for (int bit : {1, 2, 4})
      if (!(i & bit)) {
        const vtkIdType ids[2] = {i, i | bit};
        edges->InsertNextCell(2, ids);
      }
  vtkNew<vtkPolyData> outline;
  outline->SetPoints(cp);
  outline->SetLines(edges);
  auto edge_actor = actor_for(outline);
  edge_actor->SetUserMatrix(M);
  const Eigen::Vector3d dark = rgb * kStyle.edge_darkening;
  edge_actor->GetProperty()->SetColor(dark.x(), dark.y(), dark.z());
  edge_actor->GetProperty()->SetLineWidth(kStyle.edge_width);
  edge_actor->GetProperty()->LightingOff();
  ren->AddActor(edge_actor);
}

void add_polyline(vtkRenderer* ren, const ScenePolyline& l, bool strip) {
  if (l.points.empty()) return;
  vtkNew<vtkPoints> pts;
  for (const auto& p : l.points) pts->InsertNextPoint(p.x(), p.y(), p.z());
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkPolyData> data;
  data->SetPoints(pts);
  if (strip && l.points.size() >= 2) {
    cells->InsertNextCell(static_cast<vtkIdType>(l.points.size()));
    for (vtkIdType i = 0; i < static_cast<vtkIdType>(l.points.size()); ++i) cells->InsertCellPoint(i);
    data->SetLines(cells);
  } else {
    for (vtkIdType i = 0; i < static_cast<vtkIdType>(l.points.size()); ++i) cells->InsertNextCell(1, &i);
    data->SetVerts(cells);
  }
  auto actor = actor_for(data);
  actor->GetProperty()->SetColor(l.colour.x(), l.colour.y(), l.colour.z());
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetLineWidth(kStyle.trajectory_width);
  actor->GetProperty()->SetPointSize(strip ? 2 * kStyle.point_size : kStyle.point_size);
  ren->AddActor(actor);
}

// 1, 2 or 5 times a power of ten, about span / lines.
double grid_step(double span, int lines) {
  const double raw = std::max(span, 1e-3) / lines;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

// Grid lines on the plane y = floor (glTF's up is +Y), spaced for `focus`, covering `b` with one
// step to spare.
double add_grid(vtkRenderer* ren, const Box3& focus, const Box3& b, double floor) {
  const double step = grid_step(std::max(focus.sizes().x(), focus.sizes().z()), kStyle.grid_lines);
  const double x0 = std::floor(b.min().x() / step - 1) * step, x1 = std::ceil(b.max().x() / step + 1) * step;
  const double z0 = std::floor(b.min().z() / step - 1) * step, z1 = std::ceil(b.max().z() / step + 1) * step;
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> lines;
  auto segment = [&](double xa, double za, double xb, double zb) {
    const vtkIdType a = pts->InsertNextPoint(xa, floor, za), c = pts->InsertNextPoint(xb, floor, zb);
    const vtkIdType ids[2] = {a, c};
    lines->InsertNextCell(2, ids);
  };
  for (double x = x0; x <= x1 + 1e-9; x += step) segment(x, z0, x, z1);
  for (double z = z0; z <= z1 + 1e-9; z += step) segment(x0, z, x1, z);
  vtkNew<vtkPolyData> grid;
  grid->SetPoints(pts);
  grid->SetLines(lines);
  auto actor = actor_for(grid);
  actor->GetProperty()->SetColor(kStyle.grid[0], kStyle.grid[1], kStyle.grid[2]);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetLineWidth(1.0);
  ren->AddActor(actor);
  return step;
}

void style_text(vtkTextProperty* t, int size) {
  t->SetFontSize(size);
  t->SetColor(kStyle.text[0], kStyle.text[1], kStyle.text[2]);
  t->SetFontFamilyToArial();
}

struct Label {
  vtkSmartPointer<vtkBillboardTextActor3D> actor;
  Eigen::Vector3d anchor;  // world point under the text's bottom centre
  std::string text;
  double priority = 0;     // larger keeps its place when labels collide
};

Label add_label(vtkRenderer* ren, const std::string& text, const Eigen::Vector3d& at, int size, double priority) {
  auto label = vtkSmartPointer<vtkBillboardTextActor3D>::New();
  label->SetInput(text.c_str());
  label->SetPosition(at.x(), at.y(), at.z());
  style_text(label->GetTextProperty(), size);
  label->GetTextProperty()->SetJustificationToCentered();
  label->GetTextProperty()->SetVerticalJustificationToBottom();
  label->GetTextProperty()->SetBackgroundColor(1.0, 1.0, 1.0);
  label->GetTextProperty()->SetBackgroundOpacity(0.75);
  ren->AddActor(label);
  return {label, at, text, priority};
}

// Moves labels that would cover one another up or down the picture (display offsets), the labels
// of larger objects first. Text extents are estimated from the font size. Needs the camera placed
// and the renderer in a sized window.
void arrange_labels(vtkRenderer* ren, std::vector<Label> labels, int font) {
  std::sort(labels.begin(), labels.end(), [](const Label& a, const Label& b) { return a.priority > b.priority; });
  struct Rect {
    double x0, y0, x1, y1;
    bool hits(const Rect& r) const { return x0 < r.x1 && r.x0 < x1 && y0 < r.y1 && r.y0 < y1; }
  };
  std::vector<Rect> placed;
  const double h = 1.3 * font;
  for (Label& l : labels) {
    ren->SetWorldPoint(l.anchor.x(), l.anchor.y(), l.anchor.z(), 1.0);
    ren->WorldToDisplay();
    const double* d = ren->GetDisplayPoint();
    const double half_w = 0.5 * (0.6 * font * l.text.size() + 0.4 * font);
    Rect best{d[0] - half_w, d[1], d[0] + half_w, d[1] + h};
    int offset = 0;
    for (int k = 0; k <= 12; ++k) {
      const int dy = static_cast<int>(std::lround((k % 2 ? -1 : 1) * ((k + 1) / 2) * h));  // 0, -h, +h, -2h, ...
      const Rect r{best.x0, d[1] + dy, best.x1, d[1] + dy + h};
      if (std::none_of(placed.begin(), placed.end(), [&](const Rect& p) { return p.hits(r); })) {
        offset = dy;
        break;
      }
    }
    l.actor->SetDisplayOffset(0, offset);
    placed.push_back({best.x0, d[1] + offset, best.x1, d[1] + offset + h});
  }
}

struct LegendEntry {
  std::string text;
  Eigen::Vector3d colour;
  bool line = false;
};

// A 2-D actor from polygons or lines given in pixels (origin at the bottom left).
vtkSmartPointer<vtkActor2D> pixel_actor(const std::vector<Eigen::Vector2d>& corners, bool filled,
                                        const Eigen::Vector3d& rgb, double opacity, int layer) {
  vtkNew<vtkPoints> pts;
  for (const auto& c : corners) pts->InsertNextPoint(c.x(), c.y(), 0);
  vtkNew<vtkCellArray> cells;
  const vtkIdType n = static_cast<vtkIdType>(corners.size());
  cells->InsertNextCell(filled ? n : n + 1);
  for (vtkIdType i = 0; i < n; ++i) cells->InsertCellPoint(i);
  if (!filled) cells->InsertCellPoint(0);  // closed outline
  vtkNew<vtkPolyData> data;
  data->SetPoints(pts);
  if (filled) data->SetPolys(cells);
  else data->SetLines(cells);
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor2D>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(rgb.x(), rgb.y(), rgb.z());
  actor->GetProperty()->SetOpacity(opacity);
  actor->GetProperty()->SetLineWidth(filled ? 1.0 : 2.0);
  actor->SetLayerNumber(layer);
  return actor;
}

std::vector<Eigen::Vector2d> rect(double x, double y, double w, double h) { return {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}}; }

// The legend's panel in pixels; text widths estimated from the font size.
struct LegendLayout {
  double font = 0, row = 0, pad = 0, swatch = 0, margin = 0, w = 0, h = 0;
};

LegendLayout legend_layout(const std::vector<LegendEntry>& entries, const MapRenderOptions& o) {
  LegendLayout l;
  if (entries.empty()) return l;
  l.font = std::max(12.0, std::round(o.height / 42.0));
  l.row = 1.4 * l.font, l.pad = 0.6 * l.font, l.swatch = 0.8 * l.font, l.margin = 0.5 * l.font;
  size_t longest = 0;
  for (const auto& e : entries) longest = std::max(longest, e.text.size());
  l.w = l.pad + l.swatch + 0.5 * l.font + 0.6 * l.font * longest + l.pad;
  l.h = 2 * l.pad + l.row * entries.size();
  return l;
}

// A panel at the top right (below the title's line when there is one): one row per entry, a colour
// swatch (or a line) and dark text.
void add_legend(vtkRenderer* ren, const std::vector<LegendEntry>& entries, const MapRenderOptions& o, double title_px) {
  if (entries.empty()) return;
  const auto [font, row, pad, swatch, margin, w, h] = legend_layout(entries, o);
  const double x0 = o.width - margin - w, y0 = o.height - margin - h - (o.title.empty() ? 0.0 : 1.5 * title_px);
  const Eigen::Vector3d panel(1, 1, 1), border(0.6, 0.6, 0.6);
  ren->AddViewProp(pixel_actor(rect(x0, y0, w, h), true, panel, 0.9, 0));
  ren->AddViewProp(pixel_actor(rect(x0, y0, w, h), false, border, 1.0, 1));
  for (size_t i = 0; i < entries.size(); ++i) {
    const LegendEntry& e = entries[i];
    const double y = y0 + h - pad - row * (i + 1) + 0.5 * (row - font);  // bottom of this row's text
    const double sx = x0 + pad, sy = y + 0.5 * (font - swatch) + 0.1 * font;
    if (e.line)
      ren->AddViewProp(pixel_actor(rect(sx, sy + 0.4 * swatch, swatch, 0.2 * swatch), true, e.colour, 1.0, 1));
    else {
      ren->AddViewProp(pixel_actor(rect(sx, sy, swatch, swatch), true, e.colour, 1.0, 1));
      ren->AddViewProp(pixel_actor(rect(sx, sy, swatch, swatch), false, e.colour * kStyle.edge_darkening, 1.0, 2));
    }
    vtkNew<vtkTextActor> t;
    t->SetInput(e.text.c_str());
    style_text(t->GetTextProperty(), static_cast<int>(font));
    t->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
    t->GetPositionCoordinate()->SetValue(sx + swatch + 0.5 * font, y);
    t->SetLayerNumber(1);
    ren->AddViewProp(t);
  }
}

void add_text(vtkRenderer* ren, const std::string& text, double x, double y, int size, bool top) {
  vtkNew<vtkTextActor> t;
  t->SetInput(text.c_str());
  style_text(t->GetTextProperty(), size);
  if (top) t->GetTextProperty()->SetVerticalJustificationToTop();
  t->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  t->GetPositionCoordinate()->SetValue(x, y);
  ren->AddViewProp(t);
}

// Puts the camera so that `focus` fills kStyle.fill of the picture: straight down for the top view
// (parallel projection, world x to the right), from above and in front for the oblique view.
// The map is fitted left of a column of `reserved_px` kept free at the right (the legend's).
// Returns what the ground grid should cover: the whole picture in the top view, `focus` otherwise.
Box3 place_camera(vtkRenderer* ren, const Box3& focus, const MapRenderOptions& o, double reserved_px) {
  reserved_px = std::clamp(reserved_px, 0.0, 0.4 * o.width);
  const double aspect = (o.width - reserved_px) / o.height;
  const Eigen::Vector3d c = focus.center();
  const double diag = std::max(focus.diagonal().norm(), 1.0);
  Eigen::Vector3d forward, up;  // camera looks along forward; up is the picture's up
  if (o.view == MapView::Top) {
    forward = -Eigen::Vector3d::UnitY();
    up = -Eigen::Vector3d::UnitZ();
  } else {
    const double el = kStyle.oblique_elevation_deg * M_PI / 180, az = kStyle.oblique_azimuth_deg * M_PI / 180;
    const Eigen::Vector3d from(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
    forward = -from;
    up = Eigen::Vector3d::UnitY();
  }
  const Eigen::Vector3d right = forward.cross(up).normalized();
  up = right.cross(forward).normalized();

  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetViewUp(up.x(), up.y(), up.z());
  double distance = 0, shift = 0;  // shift: world units moving the map left of the reserved column
  Box3 cover = focus;
  if (o.view == MapView::Top) {
    double half_h = 0;
    for (const auto& p : corners(focus)) {
      const Eigen::Vector3d d = p - c;
      half_h = std::max({half_h, std::abs(d.dot(up)), std::abs(d.dot(right)) / aspect});
    }
    cam->ParallelProjectionOn();
    const double scale = std::max(half_h, 0.5) / kStyle.fill;
    cam->SetParallelScale(scale);
    shift = 0.5 * reserved_px * 2 * scale / o.height;
    const double half_w = scale * o.width / o.height;
    cover.extend(c + shift * right + scale * up + half_w * right);
    cover.extend(c + shift * right - scale * up - half_w * right);
    distance = 2 * diag + 10;
  } else {
    const double tan_v = std::tan(0.5 * kStyle.oblique_view_angle_deg * M_PI / 180) * kStyle.fill;
    const double tan_h = tan_v * aspect;
    for (const auto& p : corners(focus)) {
      const Eigen::Vector3d d = p - c;
      distance = std::max({distance, std::abs(d.dot(up)) / tan_v - d.dot(forward),
                           std::abs(d.dot(right)) / tan_h - d.dot(forward)});
    }
    distance = std::max(distance, 1.0);
    shift = 0.5 * reserved_px * 2 * distance * std::tan(0.5 * kStyle.oblique_view_angle_deg * M_PI / 180) / o.height;
    cam->ParallelProjectionOff();
    cam->SetViewAngle(kStyle.oblique_view_angle_deg);
  }
  const Eigen::Vector3d target = c + shift * right, eye = target - distance * forward;
  cam->SetFocalPoint(target.x(), target.y(), target.z());
  cam->SetPosition(eye.x(), eye.y(), eye.z());
  return cover;
}

std::string format_step(double step) {
  char buf[32];
  if (step >= 1) std::snprintf(buf, sizeof buf, "%g m", step);
  else std::snprintf(buf, sizeof buf, "%g cm", step * 100);
  return buf;
}

}  // namespace

void render_map_png(const MapScene& scene, const fs::path& png, const MapRenderOptions& o) {
  if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
    throw std::invalid_argument("picture size must be 16-16384 pixels a side");
  if (auto problem = display_problem()) throw std::runtime_error(*problem);

  // What the camera frames: objects and trajectory; the points only when there is nothing else
  // (map points reach far beyond the mapped area).
  Box3 focus, all;
  for (const auto& obj : scene.objects) focus.extend(world_bounds(obj));
  for (const auto& l : scene.lines)
    for (const auto& p : l.points) focus.extend(p);
  all = focus;
  for (const auto& l : scene.points)
    for (const auto& p : l.points) all.extend(p);
  if (focus.isEmpty()) focus = all;
  if (focus.isEmpty()) focus = Box3(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));
  // Floor: the lowest object bottom, else the lowest point of the focus.
  double floor = focus.min().y();
  bool have_objects = false;
  for (const auto& obj : scene.objects) {
    const Box3 b = world_bounds(obj);
    if (b.isEmpty()) continue;
    floor = have_objects ? std::min(floor, b.min().y()) : b.min().y();
    have_objects = true;
  }

  vtkNew<vtkRenderer> ren;
  ren->SetBackground(kStyle.background[0], kStyle.background[1], kStyle.background[2]);
  std::map<std::string, std::pair<int, Eigen::Vector3d>> classes;  // count and colour by class
  for (const auto& obj : scene.objects) {
    auto& entry = classes[obj.label];
    entry.first += 1;
    entry.second = obj.colour.head<3>().cast<double>();
  }
  size_t point_count = 0;
  for (const auto& p : scene.points) point_count += p.points.size();
  std::vector<LegendEntry> legend;
  for (const auto& [label, e] : classes) legend.push_back({label + ": " + std::to_string(e.first), e.second, false});
  if (!scene.lines.empty()) legend.push_back({"trajectory", scene.lines.front().colour.head<3>().cast<double>(), true});
  if (point_count > 0)
    legend.push_back({"map points: " + std::to_string(point_count), scene.points.front().colour.head<3>().cast<double>(), false});
  const LegendLayout layout = legend_layout(legend, o);

  const Box3 cover = place_camera(ren, focus, o, legend.empty() ? 0.0 : layout.w + 2 * layout.margin);
  const double step = add_grid(ren, focus, cover, floor);
  const int label_px = std::max(12, o.height / 48);
  for (const auto& obj : scene.objects) add_object(ren, obj);
  std::vector<Label> labels;
  for (const auto& obj : scene.objects) {
    const Box3 b = world_bounds(obj);
    if (b.isEmpty()) continue;
    const Eigen::Vector3d top(b.center().x(), b.max().y() + 0.02 * focus.diagonal().norm(), b.center().z());
    labels.push_back(add_label(ren, obj.label, top, label_px, b.sizes().x() * b.sizes().z()));
  }
  for (const auto& l : scene.lines) add_polyline(ren, l, true);
  for (const auto& p : scene.points) add_polyline(ren, p, false);

  const int text_px = std::max(12, o.height / 40);
  add_legend(ren, legend, o, text_px);
  if (!o.title.empty()) add_text(ren, o.title, 0.01, 0.99, text_px, true);
  add_text(ren,
           counted(scene.objects.size(), "object") + "; grid " + format_step(step) +
               (o.view == MapView::Top ? "; top view" : "; oblique view"),
           0.01, 0.01, std::max(11, text_px * 3 / 4), false);

  ren->ResetCameraClippingRange();

  vtkNew<vtkRenderWindow> win;
  win->SetOffScreenRendering(1);
  win->SetMultiSamples(8);
  win->SetSize(o.width, o.height);
  win->AddRenderer(ren);
  arrange_labels(ren, labels, label_px);
  win->Render();

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(win);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->WriteToMemoryOn();
  writer->Write();
  vtkUnsignedCharArray* bytes = writer->GetResult();
  if (bytes == nullptr || bytes->GetNumberOfValues() == 0) throw std::runtime_error("VTK produced no PNG data for " + png.string());
  const auto* p = bytes->GetPointer(0);
  slam::io::write_file_atomic(png, std::string(reinterpret_cast<const char*>(p), static_cast<size_t>(bytes->GetNumberOfValues())));
}

std::string counted(size_t n, const std::string& noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); }

}  // namespace wardmap::semantics
