#pragma once
// ASCII DXF group codes and the entities flat.dxf uses (LWPOLYLINE, LINE, CIRCLE, POINT, TEXT),
// with the fixed handles of the drawing's structure (dxf/document.hpp).

#include <plyfit/kernel/types.hpp>

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace plyfit::exporters::dxf {

/// Layer names and ACI colours.
struct LayerDef {
  const char* name;
  int colour;
};
constexpr LayerDef kLayers[] = {{"0", 7},        {"OUTLINE", 7}, {"HOLES", 7}, {"THREADS", 8},
                                {"BASEPATH", 5}, {"ORIGIN", 3},  {"GRAIN", 4}, {"SHEAR_WARN", 1},
                                {"LABELS", 7},   {"DART", 6}};
constexpr int kLayerCount = static_cast<int>(sizeof(kLayers) / sizeof(kLayers[0]));
/// A layer of a drawing whose layers are not flat.dxf's.
struct Layer {
  std::string name;
  int colour = 7;
};

/// The layer that is in the file only with ExportOptions::dxf_threads.
constexpr const char* kThreadsLayer = "THREADS";

/// Fixed handles of the drawing's structure; entities get handles from kFirstEntityHandle on.
enum Handle : unsigned {
  kRootDict = 0x1,
  kGroupDict,
  kLayoutDict,
  kMlineStyleDict,
  kMlineStyleStandard,
  kPlotStyleDict,
  kPlotStyleNormal,
  kLayoutModel,
  kLayoutPaper,
  kVportTable,
  kVportActive,
  kLtypeTable,
  kLtypeByBlock,
  kLtypeByLayer,
  kLtypeContinuous,
  kLayerTable,
  kStyleTable,
  kStyleStandard,
  kViewTable,
  kUcsTable,
  kAppidTable,
  kAppidAcad,
  kDimstyleTable,
  kDimstyleStandard,
  kBlockRecordTable,
  kBlockRecordModel,
  kBlockRecordPaper,
  kBlockModel,
  kEndblkModel,
  kBlockPaper,
  kEndblkPaper,
  kFirstLayerHandle,  // one per layer
  kFirstEntityHandle = kFirstLayerHandle + kLayerCount,
};

/// User text for a DXF string value: printable ASCII and U+00A0..U+00FF as single bytes of the
/// file's code page (ANSI_1252), other characters as \U+XXXX (AutoCAD decodes these), the
/// AutoCAD control sequences (%%x and ^x) neutralised, no line breaks.
std::string dxf_text(const std::string& s);

/// Group codes and values, and entities owned by *Model_Space, numbered from
/// kFirstEntityHandle.
class Writer {
 public:
  /// Entities numbered from `first_handle` (after the layers' handles).
  explicit Writer(unsigned first_handle = kFirstEntityHandle) : next_(first_handle) {}
  /// A group: its code right-aligned in three columns, as AutoCAD writes them, then the value.
  void tag(int code, const std::string& value);
  void tag(int code, int value) { tag(code, std::to_string(value)); }
  /// Integer groups in order.
  void tags(std::initializer_list<std::pair<int, int>> groups);
  /// A real in its shortest exact decimal form.
  void real(int code, double value);
  /// Real groups in order.
  void reals(std::initializer_list<std::pair<int, double>> groups);
  void handle(int code, unsigned h);
  /// A point: codes base, base + 10, base + 20 (z = 0).
  void point(const Vec2& p, int base = 10);

  void polyline(const char* layer, const std::vector<Vec2>& pts, bool closed);
  void line(const char* layer, const Vec2& a, const Vec2& b);
  void circle(const char* layer, const Vec2& c, double r);
  void dot(const char* layer, const Vec2& p);
  /// `s` is user text, escaped here with dxf_text(); `rotation` in degrees.
  void text(const char* layer, const Vec2& at, double height, const std::string& s,
            double rotation = 0.0);

  unsigned next_handle() const { return next_; }
  std::string& out() { return out_; }

 private:
  void entity_head(const char* type, const char* layer, const char* subclass);
  std::string out_;
  unsigned next_;
};

/// The first entity handle of a drawing with these layers (DocumentInfo::layers).
inline unsigned first_entity_handle(const std::vector<Layer>& layers) {
  return kFirstLayerHandle + static_cast<unsigned>(layers.size());
}

}  // namespace plyfit::exporters::dxf
