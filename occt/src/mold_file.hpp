#pragma once
// Code shared by the STEP and IGES importers: everything after a format's reader has turned
// the file into an OpenCASCADE shape. The face walk and listing (FaceInfo without any
// conversion), the conversion of one face to kernel data (NURBS surface, trim polylines,
// seams, orientation), the guard that turns OpenCASCADE exceptions and signals into Errors,
// the silencing of OpenCASCADE's messages and the summaries of its check lists.
//
// Private to plyfit_importers: OpenCASCADE headers are allowed here, never in a public header.

#include <plyfit/importers/importers.hpp>

#include "face_measure.hpp"
#include "occt_failure.hpp"

#include <Interface_CheckIterator.hxx>
#include <Message_ProgressIndicator.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_Reader.hxx>

#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace plyfit::importers::occt {

/// A progress indicator whose only job is to stop a transfer that runs past a deadline
/// (OpenCASCADE's readers poll UserBreak() while they transfer entities).
class Deadline : public Message_ProgressIndicator {
 public:
  /// Deadline `seconds` from now.
  explicit Deadline(double seconds);
  /// True once the deadline has passed.
  bool expired() const;
  /// The time limit this deadline was made with, seconds.
  double seconds() const { return seconds_; }

 protected:
  Standard_Boolean UserBreak() override { return expired(); }
  void Show(const Message_ProgressScope&, const Standard_Boolean) override {}

 private:
  std::chrono::steady_clock::time_point end_;
  double seconds_;
};

/// What a format's reader hands over to the shared code.
struct ReadOutput {
  TopoDS_Shape shape;             ///< every transferred root, as one shape
  std::string schema;             ///< STEP schema, or IGES version and sending system
  std::string unit;               ///< the file's length unit, as the file names it
  std::vector<Warning> warnings;  ///< the reader's messages, summarised (reader_checks())
  /// Names of the entities that produced transferred faces, wires and edges.
  std::vector<std::pair<TopoDS_Shape, std::string>> shape_names;
  /// The file's length precision in millimetres (see file_precision()).
  double precision = 0.0;
  /// The entity of the file that made each face ("#12", "DE 5"; entity_label()).
  std::vector<std::pair<TopoDS_Shape, std::string>> face_entities;
};

/// A format's reading step: reads `path` into a shape (units converted to millimetres).
/// Errors are messages without the path (the caller prefixes it).
using ReadFunction = std::function<Result<ReadOutput>(const std::string& path, Deadline& deadline)>;

/// The format a file's first bytes look like.
enum class Sniffed { kStep, kIges, kUnknown };

/// Looks at the first bytes of `head` (the start of a file): STEP Part 21 or IGES.
Sniffed sniff(const std::string& head);

/// Checks that `path` exists, is a regular non-empty file, looks like `format_key` ("step" or
/// "iges") and is complete (its trailer or terminate section is there); the format it is.
Result<Sniffed> check_file_head(const std::string& path, const std::string& format_key);

/// Tests: PLYFIT_DEBUG_READER_FAULT=segv or =stack makes the guarded read fault as a broken
/// reader would (a segmentation fault; a stack overflow by a recursion without end).
void debug_reader_fault();

/// Silences OpenCASCADE's default messenger (idempotent; called by open_with()).
void prepare_occt();

/// While alive, OpenCASCADE's signal handlers (OSD::SetSignal) are installed so that a fault
/// inside an OCC_CATCH_SIGNALS scope becomes an OSD_Signal exception; the previous handlers
/// (the host program's, a test framework's) are restored on destruction.
class SignalScope {
 public:
  SignalScope();
  ~SignalScope();
  SignalScope(const SignalScope&) = delete;
  SignalScope& operator=(const SignalScope&) = delete;

 private:
  struct Saved;
  Saved* saved_;
};

/// Opens `path` with a format's reader and lists its faces. Checks first that the file exists,
/// is a regular non-empty file and looks like `format_key` ("step" or "iges"); then reads it
/// under the guard and deadline.
Result<std::unique_ptr<MoldFile>> open_with(const std::string& path, const std::string& format_key,
                                            const ImportOptions& options, const ReadFunction& read);

/// Reads `path` with a format's reader, as open_with() does, into its shape without listing
/// faces: the file checks, then the read under the guard and deadline.
Result<ReadOutput> read_guarded(const std::string& path, const std::string& format_key,
                                const ImportOptions& options, const ReadFunction& read);

/// Reads `path` with a format's reader and returns its curves (Importer::curves): the edges
/// of its shape that bound no face, else every face's edges. Defined in curve_reader.cpp.
Result<std::vector<FileCurve>> curves_with(const std::string& path, const std::string& format_key,
                                           const ImportOptions& options, const ReadFunction& read);

/// Reads `path` with an OpenCASCADE reader (STEP or IGES, `format_name` for messages) and
/// sets the length unit of its output to millimetres. Errors have no path prefix.
Status read_file(XSControl_Reader& reader, const std::string& path, const std::string& format_name);

/// Transfers every root of a reader's model (under `deadline`) into `out`: the shape, the
/// load and transfer check summaries, the face names found by `name_of` and the faces' entities.
void transfer_roots(XSControl_Reader& reader, Deadline& deadline,
                    const std::function<std::string(const Handle(Standard_Transient) &)>& name_of,
                    ReadOutput& out);

/// The length precision (mm) a reader works to: a STEP file's uncertainty measure, an IGES
/// file's global-section resolution, each in the file's unit converted to millimetres; the
/// reader's default precision (read.precision.val) when the file states none. Defined in
/// occt_shell.cpp.
double file_precision(XSControl_Reader& reader);

/// Tag of a face's edge in its trim loops (TrimLoop::edges).
using EdgeTag = std::function<std::int32_t(const TopoDS_Edge&)>;

/// Converts one face to kernel data (MoldFile::convert_face). With `tag`, the face has explicit
/// trim loops even when its natural boundary bounds it, and loop segment k carries
/// (*tag)(the edge of `face` it was sampled from) in TrimLoop::edges.
Result<FaceData> convert_face(const TopoDS_Face& face, const FaceInfo& info, const Tolerances& tol,
                              const EdgeTag* tag);

/// What sewing a file's faces into a shell needs from the opened file.
struct ShellInput {
  const std::string& source;                ///< the file's path, for messages
  const TopTools_IndexedMapOfShape& faces;  ///< the file's faces in index order (1-based map)
  double precision;                         ///< the file's precision, mm (file_precision())
  const ImportOptions& options;
  /// The listing entry of face i, or an error naming the file and the face.
  std::function<Result<FaceInfo>(int)> describe;
};

/// Sews faces `indices` of a file (empty: all) into a shell and converts them
/// (MoldFile::convert_shell); what the sewing finds (several components, non-manifold edges,
/// faces reoriented) is appended to `warnings`. Defined in shell_sewing.cpp.
Result<ShellData> sew_faces(const ShellInput& input, const std::vector<int>& indices,
                            std::vector<Warning>& warnings);

/// The fails and warnings of a check list at `stage` ("load", "transfer") as one warning
/// (WarningCode::kReaderMessages: their counts and the most frequent of OpenCASCADE's messages,
/// which are its data); none when the list has neither.
std::optional<Warning> reader_checks(const Interface_CheckIterator& checks,
                                     const std::string& stage);

/// The names of the entities of `process` that produced faces (or any shape), via `name_of`.
std::vector<std::pair<TopoDS_Shape, std::string>> shape_names(
    const Handle(Transfer_TransientProcess) & process,
    const std::function<std::string(const Handle(Standard_Transient) &)>& name_of);

/// A string of OpenCASCADE, trimmed of blanks; empty for a null handle.
std::string text(const Handle(TCollection_HAsciiString) & s);

/// What an error of the module blames: the file, the face (-1: none) and the file's entity or
/// the step it happened in ("#12", "sewing faces 0-3").
struct Blame {
  std::string input;
  int face = -1;
  std::string where;
};

/// `e`, blaming `at` for what it does not name already (the innermost knows best).
inline Error blamed(Error e, const Blame& at) {
  if (e.input.empty()) e.input = at.input;
  if (e.face < 0) e.face = at.face;
  if (e.where.empty()) e.where = at.where;
  return e;
}

/// Runs `f` (which returns a Result) so that an OpenCASCADE exception (ErrorCode::kOcctFailed),
/// a fault turned into an exception (OCC_CATCH_SIGNALS), running out of memory or another C++
/// exception becomes an Error; every error blames `at` (blamed()).
template <typename F>
auto guarded(const Blame& at, F&& f) -> decltype(f()) {
  const SignalScope signals;
  try {
    OCC_CATCH_SIGNALS
    auto r = f();
    if (!r) return blamed(r.error(), at);
    return r;
  } catch (const Standard_Failure& e) {
    return blamed(Error{ErrorCode::kOcctFailed, {}, plyfit::occt::failure_values(e)}, at);
  } catch (const std::bad_alloc&) {
    return blamed(Error{ErrorCode::kOutOfMemory}, at);
  } catch (const std::exception& e) {
    return blamed(Error{ErrorCode::kUnexpectedException, {}, {std::string(e.what())}}, at);
  }
}

}  // namespace plyfit::importers::occt
