#pragma once
// The structure of an R2000 (AC1015) DXF file around its entities: every table and object
// AutoCAD requires (handles, BLOCK_RECORDs, the model and paper space layouts, the OBJECTS root
// dictionary). Nothing depends on the clock or on hash order.

#include "dxf/writer.hpp"

#include <string>
#include <vector>

namespace plyfit::exporters::dxf {

/// What the file's header and tables say about the drawing.
struct DocumentInfo {
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();  ///< the drawing's extents
  double text_height = 0.0;                   ///< $TEXTSIZE, the Standard style's height
  bool threads_layer = false;                 ///< the THREADS layer is defined
  bool dart_layer = false;                    ///< the DART layer is defined
  /// The drawing's own layers (layer 0 first), their handles from kFirstLayerHandle on, the
  /// entities' after them (Writer(first_entity_handle(layers))); empty: flat.dxf's (kLayers).
  std::vector<Layer> layers;
};

/// The whole file: HEADER, CLASSES, TABLES, BLOCKS, the ENTITIES `entities` wrote (their
/// handles set $HANDSEED), OBJECTS.
std::string document(Writer& entities, const DocumentInfo& info);

}  // namespace plyfit::exporters::dxf
