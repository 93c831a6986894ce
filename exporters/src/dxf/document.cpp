#include "dxf/document.hpp"

#include <algorithm>
#include <tuple>
#include <vector>

namespace plyfit::exporters::dxf {

namespace {

void begin_section(Writer& f, const char* name) {
  f.tag(0, "SECTION");
  f.tag(2, name);
}

void end_section(Writer& f) {
  f.tag(0, "ENDSEC");
}

void header(Writer& f, const DocumentInfo& info, unsigned handseed) {
  begin_section(f, "HEADER");
  f.tag(9, "$ACADVER");
  f.tag(1, "AC1015");
  f.tag(9, "$DWGCODEPAGE");
  f.tag(3, "ANSI_1252");
  f.tag(9, "$INSBASE");
  f.point(Vec2::Zero());
  f.tag(9, "$EXTMIN");
  f.point(info.lo);
  f.tag(9, "$EXTMAX");
  f.point(info.hi);
  f.tag(9, "$LIMMIN");
  f.reals({{10, info.lo.x()}, {20, info.lo.y()}});
  f.tag(9, "$LIMMAX");
  f.reals({{10, info.hi.x()}, {20, info.hi.y()}});
  f.tag(9, "$TEXTSIZE");
  f.real(40, info.text_height);
  f.tag(9, "$TEXTSTYLE");
  f.tag(7, "Standard");
  f.tag(9, "$CLAYER");
  f.tag(8, "0");
  // Decimal units, 4 decimals, millimetres, metric.
  for (const auto& [name, value] :
       {std::pair{"$LUNITS", 2}, {"$LUPREC", 4}, {"$INSUNITS", 4}, {"$MEASUREMENT", 1}}) {
    f.tag(9, name);
    f.tag(70, value);
  }
  f.tag(9, "$HANDSEED");
  f.handle(5, handseed);
  end_section(f);
}

void classes(Writer& f) {
  begin_section(f, "CLASSES");
  const char* classes[][3] = {{"ACDBDICTIONARYWDFLT", "AcDbDictionaryWithDefault", "0"},
                              {"ACDBPLACEHOLDER", "AcDbPlaceHolder", "0"},
                              {"LAYOUT", "AcDbLayout", "0"}};
  for (const auto& c : classes) {
    f.tag(0, "CLASS");
    f.tag(1, c[0]);
    f.tag(2, c[1]);
    f.tag(3, "ObjectDBX Classes");
    f.tag(90, c[2]);
    f.tag(280, 0);
    f.tag(281, 0);
  }
  end_section(f);
}

void table(Writer& f, const char* name, unsigned h, int count) {
  f.tag(0, "TABLE");
  f.tag(2, name);
  f.handle(5, h);
  f.handle(330, 0);
  f.tag(100, "AcDbSymbolTable");
  f.tag(70, count);
}

void end_table(Writer& f) {
  f.tag(0, "ENDTAB");
}

void record(Writer& f, const char* type, unsigned h, unsigned owner, const char* subclass,
            const std::string& name) {
  f.tag(0, type);
  f.handle(std::string(type) == "DIMSTYLE" ? 105 : 5, h);
  f.handle(330, owner);
  f.tag(100, "AcDbSymbolTableRecord");
  f.tag(100, subclass);
  f.tag(2, name);
  f.tag(70, 0);
}

// The active viewport, centred on the drawing.
void vport_table(Writer& f, const DocumentInfo& info) {
  table(f, "VPORT", kVportTable, 1);
  record(f, "VPORT", kVportActive, kVportTable, "AcDbViewportTableRecord", "*Active");
  const Vec2 centre = 0.5 * (info.lo + info.hi);
  const double view_h = 1.1 * std::max(info.hi.y() - info.lo.y(), info.hi.x() - info.lo.x());
  f.reals({{10, 0.0},
           {20, 0.0},
           {11, 1.0},
           {21, 1.0},
           {12, centre.x()},
           {22, centre.y()},
           {13, 0.0},
           {23, 0.0},
           {14, 1.0},
           {24, 1.0},
           {15, 1.0},
           {25, 1.0},
           {16, 0.0},
           {26, 0.0},
           {36, 1.0},
           {17, 0.0},
           {27, 0.0},
           {37, 0.0},
           {40, view_h > 0 ? view_h : 1.0},
           {41, 1.5},
           {42, 50.0},
           {43, 0.0},
           {44, 0.0},
           {50, 0.0},
           {51, 0.0}});
  f.tags({{71, 0}, {72, 1000}, {73, 1}, {74, 3}, {75, 0}, {76, 0}, {77, 0}, {78, 0}});
  end_table(f);
}

void ltype_table(Writer& f) {
  table(f, "LTYPE", kLtypeTable, 3);
  for (const auto& [h, name] : {std::pair{kLtypeByBlock, "ByBlock"},
                                {kLtypeByLayer, "ByLayer"},
                                {kLtypeContinuous, "Continuous"}}) {
    record(f, "LTYPE", h, kLtypeTable, "AcDbLinetypeTableRecord", name);
    f.tag(3, h == kLtypeContinuous ? "Solid line" : "");
    f.tags({{72, 65}, {73, 0}});
    f.real(40, 0.0);
  }
  end_table(f);
}

// A layer's record.
void layer_record(Writer& f, unsigned handle, const std::string& name, int colour) {
  record(f, "LAYER", handle, kLayerTable, "AcDbLayerTableRecord", name.c_str());
  f.tag(62, colour);
  f.tag(6, "Continuous");
  f.tag(370, -3);
  f.handle(390, kPlotStyleNormal);
}

void layer_table(Writer& f, const DocumentInfo& info) {
  if (!info.layers.empty()) {
    table(f, "LAYER", kLayerTable, static_cast<int>(info.layers.size()));
    for (std::size_t k = 0; k < info.layers.size(); ++k)
      layer_record(f, kFirstLayerHandle + static_cast<unsigned>(k), info.layers[k].name,
                   info.layers[k].colour);
    end_table(f);
    return;
  }
  auto defined = [&](int k) {
    const std::string name = kLayers[k].name;
    return (info.threads_layer || name != kThreadsLayer) && (info.dart_layer || name != "DART");
  };
  int layer_count = 0;
  for (int k = 0; k < kLayerCount; ++k) layer_count += defined(k);
  table(f, "LAYER", kLayerTable, layer_count);
  for (int k = 0; k < kLayerCount; ++k)
    if (defined(k))
      layer_record(f, kFirstLayerHandle + static_cast<unsigned>(k), kLayers[k].name,
                   kLayers[k].colour);
  end_table(f);
}

void style_table(Writer& f, double text_height) {
  table(f, "STYLE", kStyleTable, 1);
  record(f, "STYLE", kStyleStandard, kStyleTable, "AcDbTextStyleTableRecord", "Standard");
  f.reals({{40, 0.0}, {41, 1.0}, {50, 0.0}});
  f.tag(71, 0);
  f.real(42, text_height);
  f.tag(3, "txt");
  f.tag(4, "");
  end_table(f);
}

// VIEW and UCS (empty), APPID (ACAD), DIMSTYLE (Standard).
void small_tables(Writer& f) {
  table(f, "VIEW", kViewTable, 0);
  end_table(f);
  table(f, "UCS", kUcsTable, 0);
  end_table(f);
  table(f, "APPID", kAppidTable, 1);
  record(f, "APPID", kAppidAcad, kAppidTable, "AcDbRegAppTableRecord", "ACAD");
  end_table(f);
  table(f, "DIMSTYLE", kDimstyleTable, 1);
  f.tag(100, "AcDbDimStyleTable");
  record(f, "DIMSTYLE", kDimstyleStandard, kDimstyleTable, "AcDbDimStyleTableRecord", "Standard");
  end_table(f);
}

void block_record_table(Writer& f) {
  table(f, "BLOCK_RECORD", kBlockRecordTable, 2);
  record(f, "BLOCK_RECORD", kBlockRecordModel, kBlockRecordTable, "AcDbBlockTableRecord",
         "*Model_Space");
  f.handle(340, kLayoutModel);
  record(f, "BLOCK_RECORD", kBlockRecordPaper, kBlockRecordTable, "AcDbBlockTableRecord",
         "*Paper_Space");
  f.handle(340, kLayoutPaper);
  end_table(f);
}

void tables(Writer& f, const DocumentInfo& info) {
  begin_section(f, "TABLES");
  vport_table(f, info);
  ltype_table(f);
  layer_table(f, info);
  style_table(f, info.text_height);
  small_tables(f);
  block_record_table(f);
  end_section(f);
}

// A block's BLOCK or ENDBLK entity head.
void block_head(Writer& f, const char* type, unsigned h, unsigned owner, const char* subclass) {
  f.tag(0, type);
  f.handle(5, h);
  f.handle(330, owner);
  f.tag(100, "AcDbEntity");
  if (owner == kBlockRecordPaper) f.tag(67, 1);
  f.tag(8, "0");
  f.tag(100, subclass);
}

void blocks(Writer& f) {
  begin_section(f, "BLOCKS");
  for (const auto& [b, end, owner, name] :
       {std::tuple{kBlockModel, kEndblkModel, kBlockRecordModel, "*Model_Space"},
        {kBlockPaper, kEndblkPaper, kBlockRecordPaper, "*Paper_Space"}}) {
    block_head(f, "BLOCK", b, owner, "AcDbBlockBegin");
    f.tag(2, name);
    f.tag(70, 0);
    f.point(Vec2::Zero());
    f.tag(3, name);
    f.tag(1, "");
    block_head(f, "ENDBLK", end, owner, "AcDbBlockEnd");
  }
  end_section(f);
}

void dictionary(Writer& f, unsigned h, unsigned owner,
                const std::vector<std::pair<const char*, unsigned>>& entries) {
  f.tag(0, "DICTIONARY");
  f.handle(5, h);
  f.handle(330, owner);
  f.tag(100, "AcDbDictionary");
  f.tag(281, 1);
  for (const auto& [name, target] : entries) {
    f.tag(3, name);
    f.handle(350, target);
  }
}

// The root dictionary and its groups, layouts, multiline styles and plot styles.
void dictionaries(Writer& f) {
  dictionary(f, kRootDict, 0,
             {{"ACAD_GROUP", kGroupDict},
              {"ACAD_LAYOUT", kLayoutDict},
              {"ACAD_MLINESTYLE", kMlineStyleDict},
              {"ACAD_PLOTSTYLENAME", kPlotStyleDict}});
  dictionary(f, kGroupDict, kRootDict, {});
  dictionary(f, kLayoutDict, kRootDict, {{"Model", kLayoutModel}, {"Layout1", kLayoutPaper}});
  dictionary(f, kMlineStyleDict, kRootDict, {{"Standard", kMlineStyleStandard}});
  f.tag(0, "ACDBDICTIONARYWDFLT");
  f.handle(5, kPlotStyleDict);
  f.handle(330, kRootDict);
  f.tag(100, "AcDbDictionary");
  f.tag(281, 1);
  f.tag(3, "Normal");
  f.handle(350, kPlotStyleNormal);
  f.tag(100, "AcDbDictionaryWithDefault");
  f.handle(340, kPlotStyleNormal);
  f.tag(0, "ACDBPLACEHOLDER");
  f.handle(5, kPlotStyleNormal);
  f.handle(330, kPlotStyleDict);
}

void mline_style(Writer& f) {
  f.tag(0, "MLINESTYLE");
  f.handle(5, kMlineStyleStandard);
  f.handle(330, kMlineStyleDict);
  f.tag(100, "AcDbMlineStyle");
  f.tag(2, "Standard");
  f.tag(70, 0);
  f.tag(3, "");
  f.tag(62, 256);
  f.reals({{51, 90.0}, {52, 90.0}});
  f.tag(71, 2);
  for (const double offset : {0.5, -0.5}) {
    f.real(49, offset);
    f.tag(62, 256);
    f.tag(6, "BYLAYER");
  }
}

// A layout: its plot settings (an A4 sheet, no device) and its extents.
void layout(Writer& f, unsigned h, const char* name, int tab, unsigned owner,
            const DocumentInfo& info) {
  f.tag(0, "LAYOUT");
  f.handle(5, h);
  f.handle(330, kLayoutDict);
  f.tag(100, "AcDbPlotSettings");
  f.tag(1, "");
  f.tag(2, "none_device");
  f.tag(4, "");
  f.tag(6, "");
  f.reals({{40, 0.0},
           {41, 0.0},
           {42, 0.0},
           {43, 0.0},
           {44, 297.0},
           {45, 210.0},
           {46, 0.0},
           {47, 0.0},
           {48, 0.0},
           {49, 0.0},
           {140, 0.0},
           {141, 0.0},
           {142, 1.0},
           {143, 1.0}});
  f.tags({{70, tab == 0 ? 1024 : 0}, {72, 1}, {73, 0}, {74, 5}});
  f.tag(7, "");
  f.tag(75, 16);
  f.reals({{147, 1.0}, {148, 0.0}, {149, 0.0}});
  f.tag(100, "AcDbLayout");
  f.tag(1, name);
  f.tags({{70, 1}, {71, tab}});
  f.reals({{10, 0.0}, {20, 0.0}, {11, 297.0}, {21, 210.0}});
  f.point(Vec2::Zero(), 12);
  f.point(info.lo, 14);
  f.point(info.hi, 15);
  f.real(146, 0.0);
  f.point(Vec2::Zero(), 13);
  f.reals({{16, 1.0}, {26, 0.0}, {36, 0.0}, {17, 0.0}, {27, 1.0}, {37, 0.0}});
  f.tag(76, 0);
  f.handle(330, owner);
}

void objects(Writer& f, const DocumentInfo& info) {
  begin_section(f, "OBJECTS");
  dictionaries(f);
  mline_style(f);
  layout(f, kLayoutModel, "Model", 0, kBlockRecordModel, info);
  layout(f, kLayoutPaper, "Layout1", 1, kBlockRecordPaper, info);
  end_section(f);
}

}  // namespace

std::string document(Writer& entities, const DocumentInfo& info) {
  Writer f;
  header(f, info, entities.next_handle());
  classes(f);
  tables(f, info);
  blocks(f);
  begin_section(f, "ENTITIES");
  f.out() += entities.out();
  end_section(f);
  objects(f, info);
  f.tag(0, "EOF");
  return std::move(f.out());
}

}  // namespace plyfit::exporters::dxf
