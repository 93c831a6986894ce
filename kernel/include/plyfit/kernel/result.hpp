#pragma once
/// \file Result<T>: a value or an Error; Error and Warning: codes with data.
///
/// Exceptions are kept for broken internal invariants; everything a user can get wrong (a bad
/// file, a bad option, an invalid NURBS definition) comes back as an Error: a code, the input it
/// blames and the values its text needs. Text is made only at the edge (the CLI, report.json:
/// plyfit/exporters/messages.hpp); code, tests and callers look at codes, never at words.

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace plyfit {

/// The error codes, one line each: X(Name, name) makes ErrorCode::kName, printed "name", whose
/// text is text_name() in exporters/src/render/ (a code without one does not build). Grouped by
/// the module that raises them.
#define PLYFIT_ERROR_CODES(X)                                                               \
  /* general: a broken invariant (a bug) is internal; a run stopped if asked: cancelled. */ \
  X(Internal, internal)                                                                     \
  X(Cancelled, cancelled)                                                                   \
  /* kernel: drape problem and ply */                                                       \
  X(SweepCountMismatch, sweep_count_mismatch)                                               \
  X(StartNotFinite, start_not_finite)                                                       \
  X(BaseNormalZero, base_normal_zero)                                                       \
  X(LockAngleRange, lock_angle_range)                                                       \
  X(StartNotProjected, start_not_projected)                                                 \
  X(StartNoNormal, start_no_normal)                                                         \
  X(BaseNormalTangent, base_normal_tangent)                                                 \
  X(Sweep3dZero, sweep3d_zero)                                                              \
  X(Sweep3dAlongPath, sweep3d_along_path)                                                   \
  X(Sweeps3dSameSide, sweeps3d_same_side)                                                   \
  X(SweepZero, sweep_zero)                                                                  \
  X(SweepAlongPath, sweep_along_path)                                                       \
  X(SpacingNotPositive, spacing_not_positive)                                               \
  X(PlySizeNotPositive, ply_size_not_positive)                                              \
  X(Start2dNotFinite, start2d_not_finite)                                                   \
  X(BaseDirZero, base_dir_zero)                                                             \
  X(NoSweep, no_sweep)                                                                      \
  X(TooManySweeps, too_many_sweeps)                                                         \
  X(SweepsSameSide, sweeps_same_side)                                                       \
  X(Start2dOffPly, start2d_off_ply)                                                         \
  /* kernel: search (optimize, face_start) */                                               \
  X(StartNeedsOneFace, start_needs_one_face)                                                \
  X(StartFaceNoBoundary, start_face_no_boundary)                                            \
  X(StartFaceNoInsidePoint, start_face_no_inside_point)                                     \
  X(StartFaceNoTangent, start_face_no_tangent)                                              \
  X(SearchNeedsOneFace, search_needs_one_face)                                              \
  X(SearchPathNormalAtSeed, search_path_normal_at_seed)                                     \
  /* kernel: ply definition (seed, rosette, ply angle) */                                   \
  X(SeedNotFinite, seed_not_finite)                                                         \
  X(SeedOffMold, seed_off_mold)                                                             \
  X(RosetteZero, rosette_zero)                                                              \
  X(RosetteAlongNormal, rosette_along_normal)                                               \
  X(PlyAngleRange, ply_angle_range)                                                         \
  /* kernel: ply boundary */                                                                \
  X(BoundaryEmpty, boundary_empty)                                                          \
  X(BoundaryCurvePoints, boundary_curve_points)                                             \
  X(BoundaryGap, boundary_gap)                                                              \
  X(BoundaryOffMold, boundary_off_mold)                                                     \
  X(BoundarySeedOutside, boundary_seed_outside)                                             \
  /* kernel: splices */                                                                     \
  X(RollNarrowerThanCells, roll_narrower_than_cells)                                        \
  X(SpliceOverlapNegative, splice_overlap_negative)                                         \
  X(SpliceOverlapTooWide, splice_overlap_too_wide)                                          \
  X(SpliceValueNotFinite, splice_value_not_finite)                                          \
  X(SpliceStaggerNegative, splice_stagger_negative)                                         \
  /* kernel: seed curve from a file */                                                      \
  X(SeedCurveOffMold, seed_curve_off_mold)                                                  \
  X(SeedNotOnCurve, seed_not_on_curve)                                                      \
  /* kernel: darts */                                                                       \
  X(DartCurvePoints, dart_curve_points)                                                     \
  X(DartOffMold, dart_off_mold)                                                             \
  /* kernel: geometry (NURBS), surface (faces, shells), molds, search */                    \
  /* kernel: geometry (NURBS surfaces and curves) */                                        \
  X(DegreeRange, degree_range)                                                              \
  X(TooFewPoles, too_few_poles)                                                             \
  X(KnotCount, knot_count)                                                                  \
  X(KnotNotFinite, knot_not_finite)                                                         \
  X(KnotsDecrease, knots_decrease)                                                          \
  X(KnotMultiplicity, knot_multiplicity)                                                    \
  X(EmptyDomain, empty_domain)                                                              \
  X(PoleCount, pole_count)                                                                  \
  X(WeightCount, weight_count)                                                              \
  X(PoleNotFinite, pole_not_finite)                                                         \
  X(WeightNotPositive, weight_not_positive)                                                 \
  X(CurveWeightCount, curve_weight_count)                                                   \
  X(CurvePoleNotFinite, curve_pole_not_finite)                                              \
  X(CurveWeightNotPositive, curve_weight_not_positive)                                      \
  X(PolylineTooFewPoints, polyline_too_few_points)                                          \
  X(InterpolationTooFewPoints, interpolation_too_few_points)                                \
  X(InterpolationPointsCoincide, interpolation_points_coincide)                             \
  X(InterpolationSingular, interpolation_singular)                                          \
  /* kernel: surface (faces and shells) */                                                  \
  X(TrimLoopEdgeTags, trim_loop_edge_tags)                                                  \
  X(TrimLoopTooFewPoints, trim_loop_too_few_points)                                         \
  X(TrimLoopNotFinite, trim_loop_not_finite)                                                \
  X(FaceEmpty, face_empty)                                                                  \
  X(FaceZeroSize, face_zero_size)                                                           \
  X(ShellNoFaces, shell_no_faces)                                                           \
  X(ShellTooManyFaces, shell_too_many_faces)                                                \
  X(ShellFaceIndices, shell_face_indices)                                                   \
  X(ShellEdgeCountNegative, shell_edge_count_negative)                                      \
  X(SharedEdgeRange, shared_edge_range)                                                     \
  X(SharedEdgeUses, shared_edge_uses)                                                       \
  X(SharedEdgeNotEvaluated, shared_edge_not_evaluated)                                      \
  X(ShellNotSewn, shell_not_sewn)                                                           \
  X(ShellOrientation, shell_orientation)                                                    \
  /* kernel: built-in molds and shells */                                                   \
  X(UnknownBuiltin, unknown_builtin)                                                        \
  X(BuiltinNoParameter, builtin_no_parameter)                                               \
  X(BuiltinParameterNotFinite, builtin_parameter_not_finite)                                \
  X(BuiltinParameterNotPositive, builtin_parameter_not_positive)                            \
  X(BuiltinAngleRange, builtin_angle_range)                                                 \
  X(BuiltinParameterRange, builtin_parameter_range)                                         \
  X(BuiltinIntegerRange, builtin_integer_range)                                             \
  X(BuiltinCylinderWindow, builtin_cylinder_window)                                         \
  X(BuiltinConeRadii, builtin_cone_radii)                                                   \
  X(BuiltinPlateHole, builtin_plate_hole)                                                   \
  X(BuiltinDishHole, builtin_dish_hole)                                                     \
  X(BuiltinTorusTube, builtin_torus_tube)                                                   \
  X(BuiltinTorusAngles, builtin_torus_angles)                                               \
  X(BuiltinTrimCurve, builtin_trim_curve)                                                   \
  X(BuiltinMold, builtin_mold)                                                              \
  X(BuiltinNameMissing, builtin_name_missing)                                               \
  X(BuiltinParameterSyntax, builtin_parameter_syntax)                                       \
  X(BuiltinParameterValue, builtin_parameter_value)                                         \
  /* importers and the OpenCASCADE module */                                                \
  X(FileMissing, file_missing)                                                              \
  X(FileNotRegular, file_not_regular)                                                       \
  X(FileEmpty, file_empty)                                                                  \
  X(FileWrongFormat, file_wrong_format)                                                     \
  X(FileTruncated, file_truncated)                                                          \
  X(ImportFormatUnknown, import_format_unknown)                                             \
  X(FileExtensionUnknown, file_extension_unknown)                                           \
  X(FaceIndexRange, face_index_range)                                                       \
  X(ReadTimeLimit, read_time_limit)                                                         \
  X(FileNoFaces, file_no_faces)                                                             \
  X(FaceListedTwice, face_listed_twice)                                                     \
  X(SewingToleranceInvalid, sewing_tolerance_invalid)                                       \
  X(FileNotReadable, file_not_readable)                                                     \
  X(FileNumberNotFinite, file_number_not_finite)                                            \
  X(FileNumberTooLarge, file_number_too_large)                                              \
  X(StepWordForNumber, step_word_for_number)                                                \
  X(StepNestingTooDeep, step_nesting_too_deep)                                              \
  X(StepReferenceCycle, step_reference_cycle)                                               \
  X(StepReferencesTooDeep, step_references_too_deep)                                        \
  X(FaceGeometryNotFinite, face_geometry_not_finite)                                        \
  X(FaceGeometryTooLarge, face_geometry_too_large)                                          \
  X(FaceWeightNotPositive, face_weight_not_positive)                                        \
  X(FaceToleranceInvalid, face_tolerance_invalid)                                           \
  X(FaceScaleInvalid, face_scale_invalid)                                                   \
  X(FaceAreaNotMeasured, face_area_not_measured)                                            \
  X(OcctFailed, occt_failed)                                                                \
  X(OutOfMemory, out_of_memory)                                                             \
  X(UnexpectedException, unexpected_exception)                                              \
  X(FaceNotDescribed, face_not_described)                                                   \
  X(FaceNotMeasured, face_not_measured)                                                     \
  X(FileNotParsed, file_not_parsed)                                                         \
  X(IgesNoModel, iges_no_model)                                                             \
  X(OcctModuleMissing, occt_module_missing)                                                 \
  X(OcctModuleNotLoaded, occt_module_not_loaded)                                            \
  X(OcctModuleNoEntry, occt_module_no_entry)                                                \
  X(OcctModuleOtherBuild, occt_module_other_build)                                          \
  X(OcctNoReader, occt_no_reader)                                                           \
  X(CurvesNoExtent, curves_no_extent)                                                       \
  X(CurveNotDiscretised, curve_not_discretised)                                             \
  X(EdgeNoPcurve, edge_no_pcurve)                                                           \
  X(TrimPointBudget, trim_point_budget)                                                     \
  X(FaceNoTrimLoop, face_no_trim_loop)                                                      \
  X(FaceNoSurface, face_no_surface)                                                         \
  X(NurbsConversionFailed, nurbs_conversion_failed)                                         \
  X(NurbsConversionNoFace, nurbs_conversion_no_face)                                        \
  X(NurbsConversionType, nurbs_conversion_type)                                             \
  X(FaceSurfaceInvalid, face_surface_invalid)                                               \
  X(SewingTimeLimit, sewing_time_limit)                                                     \
  X(SewingNoShape, sewing_no_shape)                                                         \
  X(SewingRemovedFace, sewing_removed_face)                                                 \
  X(SewingZeroSize, sewing_zero_size)                                                       \
  X(WriterValueTooLarge, writer_value_too_large)                                            \
  X(WriterSurfaceInvalid, writer_surface_invalid)                                           \
  X(WriterLoopCount, writer_loop_count)                                                     \
  X(WriterLoopTooFewPoints, writer_loop_too_few_points)                                     \
  X(WriterTrimCurveInvalid, writer_trim_curve_invalid)                                      \
  X(WriterLoopOffDomain, writer_loop_off_domain)                                            \
  X(WriterEdgeTags, writer_edge_tags)                                                       \
  X(WriterEdgeNotBuilt, writer_edge_not_built)                                              \
  X(WriterLoopNotJoined, writer_loop_not_joined)                                            \
  X(WriterFaceNotBuilt, writer_face_not_built)                                              \
  X(WriterFaceNotInsideTrim, writer_face_not_inside_trim)                                   \
  X(WriterHolesNotAdded, writer_holes_not_added)                                            \
  X(WriterTrimCurve3d, writer_trim_curve_3d)                                                \
  X(WriterNotTransferred, writer_not_transferred)                                           \
  X(WriterNoFace, writer_no_face)                                                           \
  X(WriterNoProtocol, writer_no_protocol)                                                   \
  X(WriterFailed, writer_failed)                                                            \
  X(WriterOcctFailed, writer_occt_failed)                                                   \
  /* exporters */                                                                           \
  X(FileNotCreated, file_not_created)                                                       \
  X(FileAlreadyClosed, file_already_closed)                                                 \
  X(FileWriteFailed, file_write_failed)                                                     \
  X(FileNotRenamed, file_not_renamed)                                                       \
  X(OutputFolderNotCreated, output_folder_not_created)                                      \
  X(UnknownOutput, unknown_output)                                                          \
  X(CurveRational, curve_rational)                                                          \
  X(CurveInvalid, curve_invalid)                                                            \
  X(CurveSetNotBuilt, curve_set_not_built)                                                  \
  X(ThreadCurveNotBuilt, thread_curve_not_built)                                            \
  X(BoundaryLoopTooSmall, boundary_loop_too_small)                                          \
  X(MoldWriterOtherBuild, mold_writer_other_build)                                          \
  /* cli */                                                                                 \
  X(UnknownCommand, unknown_command)                                                        \
  X(UnknownOption, unknown_option)                                                          \
  X(BadCommandLine, bad_command_line)                                                       \
  X(OptionNeedsValue, option_needs_value)                                                   \
  X(UnexpectedArgument, unexpected_argument)                                                \
  X(MissingArgument, missing_argument)                                                      \
  X(OptionRepeated, option_repeated)                                                        \
  X(OptionsExclusive, options_exclusive)                                                    \
  X(MissingOption, missing_option)                                                          \
  X(EmptyValue, empty_value)                                                                \
  X(NotANumber, not_a_number)                                                               \
  X(NotFinite, not_finite)                                                                  \
  X(VectorSize, vector_size)                                                                \
  X(NotAnInteger, not_an_integer)                                                           \
  X(NotABool, not_a_bool)                                                                   \
  X(OutOfRange, out_of_range)                                                               \
  X(ZeroVector, zero_vector)                                                                \
  X(UnknownValue, unknown_value)                                                            \
  X(EmptyList, empty_list)                                                                  \
  X(ListedTwice, listed_twice)                                                              \
  /* cli: scene files and the materials table (INI) */                                      \
  X(SceneCannotOpen, scene_cannot_open)                                                     \
  X(IniSyntax, ini_syntax)                                                                  \
  X(UnknownKey, unknown_key)                                                                \
  X(MaterialsCannotOpen, materials_cannot_open)                                             \
  X(MaterialsCannotRead, materials_cannot_read)                                             \
  X(NoMaterials, no_materials)                                                              \
  X(KeyOutsideMaterial, key_outside_material)                                               \
  X(MaterialNameInvalid, material_name_invalid)                                             \
  X(MaterialRepeated, material_repeated)                                                    \
  X(MaterialLabelEmpty, material_label_empty)                                               \
  X(MaterialAngleNotANumber, material_angle_not_a_number)                                   \
  X(MaterialAngleRange, material_angle_range)                                               \
  X(MaterialRollWidth, material_roll_width)                                                 \
  X(MaterialAngleMissing, material_angle_missing)                                           \
  X(WarningAboveLimit, warning_above_limit)                                                 \
  X(LimitNotPositive, limit_not_positive)                                                   \
  X(UnknownMaterial, unknown_material)                                                      \
  /* cli: curve files (ply boundaries) */                                                   \
  X(CurveFileCannotOpen, curve_file_cannot_open)                                            \
  X(CurveFileSyntax, curve_file_syntax)                                                     \
  X(CurveFileFormat, curve_file_format)                                                     \
  X(CurveNotFound, curve_not_found)                                                         \
  X(CurveFileUnreadable, curve_file_unreadable)                                             \
  X(CurveFileNoCurves, curve_file_no_curves)                                                \
  X(SeedCurveOneCurve, seed_curve_one_curve)                                                \
  /* cli: jobs and commands */                                                              \
  X(BuiltinFaceGiven, builtin_face_given)                                                   \
  X(NoFaceAtPoint, no_face_at_point)                                                        \
  X(ConnectedNeedsPoint, connected_needs_point)                                             \
  X(OptionWithout, option_without)                                                          \
  X(Interrupted, interrupted)                                                               \
  X(UnknownMoldFormat, unknown_mold_format)                                                 \
  X(BadShard, bad_shard)                                                                    \
  X(CannotCreateFolder, cannot_create_folder)                                               \
  X(FolderHoldsOtherFiles, folder_holds_other_files)                                        \
  X(CannotMoveOutputs, cannot_move_outputs)                                                 \
  X(CannotStartDrape, cannot_start_drape)                                                   \
  X(DrapeCrashed, drape_crashed)                                                            \
  X(DrapeNoOutcome, drape_no_outcome)                                                       \
  X(OutcomeUnreadable, outcome_unreadable)                                                  \
  X(DifferentMolds, different_molds)                                                        \
  X(OptimizeShell, optimize_shell)                                                          \
  X(NoFeasibleDrape, no_feasible_drape)                                                     \
  X(OptionNeedsVary, option_needs_vary)                                                     \
  /* cli: laminates */                                                                      \
  X(LaminateSection, laminate_section)                                                      \
  X(LaminateNoPlies, laminate_no_plies)                                                     \
  X(PlyNameInvalid, ply_name_invalid)                                                       \
  X(PlyRepeated, ply_repeated)                                                              \
  X(SequenceRepeated, sequence_repeated)                                                    \
  X(KeyNotInLaminate, key_not_in_laminate)                                                  \
  X(PlyException, ply_exception)                                                            \
  X(PieceWiderThanRoll, piece_wider_than_roll)

/// What went wrong (see PLYFIT_ERROR_CODES).
enum class ErrorCode : std::uint16_t {
#define PLYFIT_ENUM_ENTRY(name, snake) k##name,
  PLYFIT_ERROR_CODES(PLYFIT_ENUM_ENTRY)
#undef PLYFIT_ENUM_ENTRY
};
/// The code's name, e.g. "spacing_not_positive" (stable: printed by the CLI, checked by tests).
const char* to_string(ErrorCode code);

/// A value an error or warning carries for its text: a count or index, a measure, a name.
using MessageValue = std::variant<std::int64_t, double, std::string>;

/// An expected failure: its code, the input it blames and its data.
struct Error {
  ErrorCode code = ErrorCode::kInternal;
  /// The input it blames, as its caller knows it: a drape input by its scene key ("spacing",
  /// "start3d", "sweep2d"), a file by its path; empty when the caller adds it (Error::in()).
  std::string input;
  /// The code's values, in the order its text uses them (messages.cpp lists them per code).
  std::vector<MessageValue> values;
  /// The face (its index in the mold file) it concerns, or -1.
  int face = -1;
  /// Where in its input: a file's entity ("#12" in STEP, "DE 34" in IGES), a ply's name.
  std::string where;
  /// The error this one wraps (a face that does not convert because its surface does not): its
  /// text follows this one's.
  std::shared_ptr<const Error> cause;

  Error() = default;
  Error(ErrorCode c, std::string blamed = {}, std::vector<MessageValue> v = {})
      : code(c), input(std::move(blamed)), values(std::move(v)) {}
  /// This error, wrapping `inner` (its cause).
  Error&& because(Error inner) && {
    cause = std::make_shared<const Error>(std::move(inner));
    return std::move(*this);
  }
  /// Names the input it blames, unless it names one already (the innermost knows best).
  Error& in(const std::string& blamed) & {
    if (input.empty()) input = blamed;
    return *this;
  }
  Error&& in(const std::string& blamed) && { return std::move(in(blamed)); }
  /// Says which face it concerns, unless it says so already.
  Error&& at_face(int f) && {
    if (face < 0) face = f;
    return std::move(*this);
  }
};

/// The warning codes, as PLYFIT_ERROR_CODES: X(Name, name).
#define PLYFIT_WARNING_CODES(X)               \
  /* general */                               \
  X(Note, note)                               \
  /* kernel: drape */                         \
  X(StartFar, start_far)                      \
  X(NoCellMapped, no_cell_mapped)             \
  X(SweepMapsNoNode, sweep_maps_no_node)      \
  X(UncoveredArea, uncovered_area)            \
  X(OutlineShort, outline_short)              \
  X(PathEnds, path_ends)                      \
  X(Cancelled, cancelled)                     \
  X(NodeCap, node_cap)                        \
  X(ClothOnItself, cloth_on_itself)           \
  X(FailedNodes, failed_nodes)                \
  X(ConflictNodes, conflict_nodes)            \
  X(ThreadEnds, thread_ends)                  \
  X(PathSlit, path_slit)                      \
  /* kernel: splices */                       \
  X(SpliceStaggerUnmet, splice_stagger_unmet) \
  X(DartsNotEnough, darts_not_enough)         \
  /* importers and the OpenCASCADE module */  \
  X(ReaderMessages, reader_messages)          \
  X(FaceAreaShort, face_area_short)           \
  X(FaceAreaUnmeasured, face_area_unmeasured) \
  X(ListingFailedFaces, listing_failed_faces) \
  X(UnmeasuredFaces, unmeasured_faces)        \
  X(ShortAreaFaces, short_area_faces)         \
  X(SeparateShells, separate_shells)          \
  X(NonManifoldEdges, non_manifold_edges)     \
  X(FacesReoriented, faces_reoriented)        \
  X(ShellNotOrientable, shell_not_orientable) \
  X(TrimLoopsDropped, trim_loops_dropped)

/// What a run reports that is not an error (see PLYFIT_WARNING_CODES).
enum class WarningCode : std::uint16_t {
#define PLYFIT_ENUM_ENTRY(name, snake) k##name,
  PLYFIT_WARNING_CODES(PLYFIT_ENUM_ENTRY)
#undef PLYFIT_ENUM_ENTRY
};
/// The code's name, e.g. "start_far".
const char* to_string(WarningCode code);

/// Something a run reports that did not stop it: its code and data.
struct Warning {
  WarningCode code = WarningCode::kNote;
  std::vector<MessageValue> values;  ///< in the order its text uses them (messages.cpp)
};

/// Either a T or an Error (a minimal `tl::expected`).
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Result(Error e) : v_(std::move(e)) {}      // NOLINT(google-explicit-constructor)

  /// True when a value is held.
  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }

  /// The value; throws std::logic_error when called on an error (an internal bug).
  T& value() & {
    check();
    return std::get<0>(v_);
  }
  const T& value() const& {
    check();
    return std::get<0>(v_);
  }
  T&& value() && {
    check();
    return std::get<0>(std::move(v_));
  }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  /// The error; only valid when !ok().
  const Error& error() const { return std::get<1>(v_); }

 private:
  void check() const {
    if (!ok())
      throw std::logic_error(std::string("Result::value() on an error: ") +
                             to_string(std::get<1>(v_).code));
  }
  std::variant<T, Error> v_;
};

/// Result of an operation with no value.
struct Unit {};
using Status = Result<Unit>;
inline Status ok_status() {
  return Unit{};
}

}  // namespace plyfit
