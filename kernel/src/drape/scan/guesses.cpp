// The per-node solves of the scan and their initial guesses: two known neighbours (§5.2, the
// two-sphere solver with the guess of eqs. 10-11 or its refinements) and one known neighbour
// (§6.1, eq. 13: the plane-sphere solver).
#include "drape/scan/scanner.hpp"

#include <cmath>

namespace plyfit::detail {

namespace {
// The fold test of a two-sphere node tells the sides of the line a-b apart across the mean
// of the normals at the node and the cell's fourth corner while that mean (of two unit
// normals) is at least this long: the normals turn by less than about 174 degrees.
constexpr double kFoldMeanNormalMin = 0.1;
}  // namespace

// Solver 2 for q from neighbours a (direction da from q) and b (db): the step on the branch
// that keeps the ply's orientation, its initial guess, the solve, then the stops the solver
// cannot see (fronts that disagree, a cell that folds).
SolveResult Scanner::solve_two(const DrapeNode& q, const DrapeNode& a, ThreadDir da, double ra,
                               const DrapeNode& b, ThreadDir db, double rb) {
  TwoSphereStep step = two_sphere_step(q, a, ra, b, rb);
  GuessKind kind = GuessKind::kNone;
  const DrapeNode* corner = guess_two(q, a, da, ra, b, db, rb, step, kind);
  const std::optional<Vec2> rule_guess = step.guess;
  correct_guess(a, b, kind, step);
  SolverSettings st = st_;
  if (is_weft(da) == is_weft(db)) st.gamma_min = 0.0;  // same thread: no thread angle
  SolveResult r = solve_two_spheres(s_, step, st);
  record_guess_error(q, kind, rule_guess, r);
  // Two mapped nodes on one thread farther apart than the two links between them, or so
  // little closer that the links would pass below the face (SolveResult::no_point): fronts
  // of cloth that met from both sides of the node, and no point joins them (a conflict).
  if (is_weft(da) == is_weft(db) && r.status == SolveStatus::kFailed &&
      ((b.point - a.point).norm() > ra + rb || r.no_point)) {
    r.reason = "the fronts disagree: the thread between them would stretch";
    r.fronts_disagree = true;
  }
  // A weft and a warp neighbour farther apart than their two links, the cell's fourth corner
  // not mapped: no position of the node joins them, at any shear (the thread angle would pass
  // pi). Fronts of cloth that met around a gap of the net (a conflict), not the shear limit.
  if (!corner && is_weft(da) != is_weft(db) && r.status == SolveStatus::kShearLimit &&
      (b.point - a.point).norm() > ra + rb) {
    r.status = SolveStatus::kFailed;
    r.shear_stop = ShearStop::kNone;
    r.reason = "the fronts disagree: the links cannot meet";
    r.fronts_disagree = true;
  }
  // (A solve that found only the branch folding the cell against the ply's orientation is the
  // same fold when that solution lies on the corner's side.)
  const bool folded = r.status == SolveStatus::kFailed && r.folded_branch;
  if (corner &&
      (r.status == SolveStatus::kConverged || r.status == SolveStatus::kShearLimit || folded) &&
      r.point.allFinite() && cell_folds(r, a, b, *corner)) {
    r.status = SolveStatus::kShearLimit;
    r.shear_stop = ShearStop::kCellFolds;
    r.reason = "the cell would fold (the cloth is sheared flat)";
  }
  return r;
}

// The two-sphere step for q: the branch where the triangle (a, b, q) keeps its 2D orientation
// about the normal (where q lies on the line a-b in the ply, its sweep's side).
TwoSphereStep Scanner::two_sphere_step(const DrapeNode& q, const DrapeNode& a, double ra,
                                       const DrapeNode& b, double rb) const {
  const Vec2 e2 = b.ply - a.ply;
  double c2 = cross2(e2, q.ply - a.ply);
  if (std::abs(c2) <= opt_.tol.ply_merge_rel * ply_.d() * e2.norm()) {
    const int k = ply_.sweep_for_side(ply_.side(q.ply));
    c2 = cross2(e2, ply_.spec().sweeps[k]);
  }
  return TwoSphereStep{a.point,      a.at(),      ra, b.point, b.at(), rb, c2 > 0 ? 1.0 : -1.0,
                       std::nullopt, std::nullopt};
}

// The initial guess of step by the rule of DrapeOptions::guess (extrapolated, the paper's
// eqs. 10-11 or the parallelogram), and the cell's fourth corner, if mapped (returned, and
// step.corner).
const DrapeNode* Scanner::guess_two(const DrapeNode& q, const DrapeNode& a, ThreadDir da, double ra,
                                    const DrapeNode& b, ThreadDir db, double rb,
                                    TwoSphereStep& step, GuessKind& kind) const {
  const DrapeNode* ap = mapped_nb(a, da);  // a's predecessor on q's thread
  const DrapeNode* bp = mapped_nb(b, db);
  const DrapeNode* c = nullptr;  // the cell's fourth corner
  if (!a.id.is_path_only() && !b.id.is_path_only()) {
    c = mapped_nb(a, db);
    if (c && c->id != NodeId::regular(a.id.i + b.id.i - q.id.i, a.id.j + b.id.j - q.id.j))
      c = nullptr;
  }
  // Guesses combine parameters, so they are made only from nodes of one chart (face); across
  // a shared edge the solver starts from its planar two-circle solution instead.
  if (ap && bp && !one_chart({&a, ap, &b, bp})) ap = bp = nullptr;
  const DrapeNode* corner = c;  // kept across charts: the branch and fold tests need no (u, v)
  if (corner) step.corner = corner->point;
  if (c && !one_chart({&a, &b, c})) c = nullptr;
  auto paper = [&] {
    kind = GuessKind::kPaper;
    step.guess = two_sphere_guess(s_, a.at(), ap->at(), a.point, ap->point, ra, b.at(), bp->at(),
                                  b.point, bp->point, rb);
  };
  auto parallelogram = [&] {
    kind = GuessKind::kParallelogram;
    step.guess = a.uv + s_.delta(c->at(), b.at());
  };
  if (opt_.guess == GuessRule::kExtrapolated && c)
    kind = extrapolated_guess(q, a, da, b, db, *c, step);
  if (kind != GuessKind::kNone) {
    // step.guess is set
  } else if (opt_.guess != GuessRule::kParallelogram) {
    if (ap && bp)
      paper();
    else if (c)
      parallelogram();
  } else {
    if (c)
      parallelogram();
    else if (ap && bp)
      paper();
  }
  return corner;
}

// The cell (a, c, b, q) must not fold: q lies across the line a-b from the fourth corner c,
// about the normal. The solver kept the ply's orientation of (a, b, q); if c lies on that side
// too, the net around c is already sheared past flat, and no unfolded cell exists: the cloth
// stops there as at the shear limit. (Sides compared by the parts of q - a and c - a across
// the line: a cell is not bent by 90 degrees, and no surface evaluation is needed.)
bool Scanner::cell_folds(const SolveResult& r, const DrapeNode& a, const DrapeNode& b,
                         const DrapeNode& corner) const {
  const Vec3 e = (b.point - a.point).normalized();
  Vec3 u = r.point - a.point, w = corner.point - a.point;
  u -= u.dot(e) * e;
  w -= w.dot(e) * e;
  if (u.dot(w) < 0.0) return false;
  // A cell sheared nearly flat on a curved face has q and c both below the chord a-b by about
  // its sag, which can outweigh their offsets across it (sphere-8, 80 degrees of shear: 0.14
  // below, 0.19 across): there the sides are told by the offsets along the sideways
  // direction, across the mean of the normals at q and c (two evaluations, only for the cells
  // that seem folded; not where the normals nearly cancel, at a knife edge).
  const SurfaceNormal nq = s_.normal(r.at), nc = s_.normal(corner.at());
  const Vec3 side = (nq.n + nc.n).cross(e);
  if (!nq.ok || !nc.ok || !(side.norm() > kFoldMeanNormalMin)) return true;
  return u.dot(side) * w.dot(side) >= 0.0;
}

// GuessRule::kExtrapolated for the node across the cell (a, c, b) from c, a and b its weft
// and warp neighbours (directions da, db from the node): both threads continued through
// their last four nodes, cubic in (u, v) (equal steps: regular nodes only), if the two
// continuations agree to kExtrapolationAgreement of the cell's step; else the parallelogram
// a + b - c plus the mean twist of the two neighbouring cells. Only nodes on q's side of the
// base path are used. False if neither applies, or if the guess is not trusted (outside the
// parameter domain, or far from the parallelogram).
Scanner::GuessKind Scanner::extrapolated_guess(const DrapeNode& q, const DrapeNode& a, ThreadDir da,
                                               const DrapeNode& b, ThreadDir db, const DrapeNode& c,
                                               TwoSphereStep& step) const {
  if (is_weft(da) == is_weft(db)) return GuessKind::kNone;
  // Only nodes swept from the same side of the base path as q: across the path (and at
  // the path's own nodes, mapped by another solver) the net is not smooth.
  const int side = ply_.side(q.ply);
  // The stencil reaches 4 cells from q: far from the path it is all on q's side.
  const bool far = std::abs(cross2(ply_.base_dir(), q.ply - ply_.spec().start)) >
                   kStencilCells * far_ / kFarFromPathCells;
  auto same_side = [&](const DrapeNode& n) { return far || ply_.side(n.ply) == side; };
  if (!same_side(a) || !same_side(b) || !same_side(c)) return GuessKind::kNone;
  auto regular = [&](const DrapeNode* n, ThreadDir d) -> const DrapeNode* {
    const DrapeNode* m = n ? mapped_nb(*n, d) : nullptr;
    return (m && !m->id.is_path_only() && same_side(*m)) ? m : nullptr;
  };
  const DrapeNode* a1 = regular(&a, da);
  const DrapeNode* b1 = regular(&b, db);
  if (!a1 || !b1 || !one_chart({&a, &b, &c, a1, b1})) return GuessKind::kNone;
  const SurfaceLocation chart = a.at();  // every node of the stencil is in a's chart
  auto D = [&](const DrapeNode* x, const DrapeNode* y) { return s_.delta(x->at(), y->at()); };
  const Vec2 sp = s_.speeds(chart);
  auto scaled = [&](const Vec2& duv) { return duv.cwiseProduct(sp).norm(); };
  // A guess is trusted only near the parallelogram a + b - c (within kExtrapolationTrust of
  // the cell's step): where (u, v) is far from linear (near a pole) extrapolation is not.
  const Vec2 para = a.uv + D(&c, &b);
  const double cell = scaled(D(&c, &a));
  auto trusted = [&](const Vec2& g) {
    return scaled(s_.delta(chart.with_uv(para), chart.with_uv(g))) < kExtrapolationTrust * cell &&
           in_domain(chart, g);
  };
  const DrapeNode* a2 = regular(a1, da);
  const DrapeNode* b2 = regular(b1, db);
  const DrapeNode* a3 = regular(a2, da);
  const DrapeNode* b3 = regular(b2, db);
  if (a3 && b3 && one_chart({&a, a2, b2, a3, b3})) {
    const Vec2 ca = a.uv + 3.0 * (D(a1, &a) - D(a2, a1)) + D(a3, a2);
    const Vec2 cb = b.uv + 3.0 * (D(b1, &b) - D(b2, b1)) + D(b3, b2);
    const Vec2 gap = s_.delta(chart.with_uv(ca), chart.with_uv(cb));
    const Vec2 g = ca + 0.5 * gap;
    if (scaled(gap) < kExtrapolationAgreement * cell && trusted(g)) {
      step.guess = g;
      return GuessKind::kCubic;
    }
  }
  const DrapeNode* c1 = regular(a1, db);  // the cells next to (a, c, b): (a1, c1) and (b1, c1b)
  const DrapeNode* c1b = regular(b1, da);
  if (!c1 || !c1b || !one_chart({&a, c1, c1b})) return GuessKind::kNone;
  const Vec2 ca = D(&c, &a), cb = D(&c, &b);
  const Vec2 g = a.uv + cb + 0.5 * (ca - D(c1, a1)) + 0.5 * (cb - D(c1b, b1));
  if (!trusted(g)) return GuessKind::kNone;
  step.guess = g;
  return GuessKind::kTwist;
}

// The guess of a node whose two neighbours' guesses were made by the same rule, in the same
// chart, corrected by the mean of their guesses' errors: a rule's error varies smoothly over
// the net (near a pole, where (u, v) is far from linear, it is large but about the same from
// node to node), so the corrected guess is off by the error's change over a cell, and Newton
// takes about one iteration less (KinDrape's hemisphere 2.95 -> 2.43 per solve). A correction
// longer than kGuessCorrectionTrust of the guess's step from a is not made, nor one shorter
// than kGuessCorrectionMinRel * d: that guess is as good as its rule makes it (a plane's
// parallelogram, exact to rounding), and one iteration converges from it.
void Scanner::correct_guess(const DrapeNode& a, const DrapeNode& b, GuessKind kind,
                            TwoSphereStep& step) const {
  if (!step.guess || kind == GuessKind::kNone || !one_chart({&a, &b})) return;
  const auto ia = static_cast<std::size_t>(&a - res_.nodes.data());
  const auto ib = static_cast<std::size_t>(&b - res_.nodes.data());
  if (ia >= guess_kind_.size() || ib >= guess_kind_.size() || guess_kind_[ia] != kind ||
      guess_kind_[ib] != kind)
    return;
  const GuessError &ea = guess_error_[ia], &eb = guess_error_[ib];
  const Vec2 fix(0.5 * (static_cast<double>(ea.du) + static_cast<double>(eb.du)),
                 0.5 * (static_cast<double>(ea.dv) + static_cast<double>(eb.dv)));
  const Vec2 sp = s_.speeds(a.at());
  const double reach = s_.delta(a.at(), a.at().with_uv(*step.guess)).cwiseProduct(sp).norm();
  const double len = fix.cwiseProduct(sp).norm();
  if (len > kGuessCorrectionMinRel * st_.spacing && len < kGuessCorrectionTrust * reach)
    *step.guess += fix;
}

// Records the error of q's guess by `kind` (before any correction) when its solve converged.
void Scanner::record_guess_error(const DrapeNode& q, GuessKind kind,
                                 const std::optional<Vec2>& guess, const SolveResult& r) {
  if (!guess || kind == GuessKind::kNone || r.status != SolveStatus::kConverged) return;
  const auto iq = static_cast<std::size_t>(&q - res_.nodes.data());
  if (guess_kind_.size() <= iq) {
    guess_kind_.resize(res_.nodes.capacity(), GuessKind::kNone);
    guess_error_.resize(res_.nodes.capacity());
  }
  const Vec2 e = s_.delta(q.at().with_uv(*guess), r.at);
  guess_error_[iq] = {static_cast<float>(e.x()), static_cast<float>(e.y())};
  guess_kind_[iq] = kind;
}

// True when uv of `chart`'s face (wrapped across closed seams) lies in its parameter domain.
// An extrapolated guess past the domain edge (e.g. past a pole, where (u, v) is far from
// linear) is left to the paper's rule.
bool Scanner::in_domain(const SurfaceLocation& chart, const Vec2& uv) const {
  const SurfaceLocation w = s_.wrap(chart.with_uv(uv));
  return s_.domain(w).contains(w.uv.x(), w.uv.y());
}

// True when the given nodes (null ones ignored) are all in one chart of the surface.
bool Scanner::one_chart(std::initializer_list<const DrapeNode*> nodes) const {
  if (one_face_) return true;
  const DrapeNode* first = nullptr;
  for (const DrapeNode* n : nodes) {
    if (!n) continue;
    if (!first)
      first = n;
    else if (!s_.same_chart(first->at(), n->at()))
      return false;
  }
  return true;
}

// Solver 3 for q from its one known neighbour a (direction da from q, rest ra).
SolveResult Scanner::solve_one(const DrapeNode& q, const DrapeNode& a, ThreadDir da, double ra) {
  const Vec3 na = s_.normal(a.at()).n;
  const Vec2 q2 = q.ply - a.ply;
  Vec3 ref3;
  Vec2 ref2;
  const DrapeNode* ap = mapped_nb(a, da);  // a's predecessor on q's thread
  if (a.has(DrapeNode::kOnPath)) {
    // Next to the base path: the 2D angle between the path and the thread is kept on the
    // tangent plane (§6.1, Fig. 9); the path tangent is that of the plane section.
    ref3 = na.cross(res_.base_normal);
    if (ref3.dot(path_chord(a)) < 0) ref3 = -ref3;
    ref2 = ply_.base_dir();
  } else if (ap) {
    // Elsewhere: continue the thread along its previous segment.
    ref3 = a.point - ap->point;
    ref2 = a.ply - ap->ply;
  } else {
    // Fall back on any mapped neighbour of a, keeping the 2D angle to it.
    const DrapeNode* r = nullptr;
    for (int d = 0; d < 4 && !r; ++d) r = mapped_nb(a, static_cast<ThreadDir>(d));
    if (!r) {
      SolveResult f;
      f.reason = "no reference direction at the known neighbour";
      return f;
    }
    ref3 = r->point - a.point;
    ref2 = r->ply - a.ply;
  }
  ref3 -= ref3.dot(na) * na;
  if (!(ref3.norm() > 0.0)) {
    SolveResult f;
    f.reason = "the reference direction is normal to the surface";
    return f;
  }
  const double theta = std::atan2(cross2(ref2, q2), ref2.dot(q2));
  const Vec3 dir = rotate_about(ref3.normalized(), na, theta);
  return solve_plane_sphere(s_, {a.point, a.at(), ra, dir}, st_);
}

}  // namespace plyfit::detail
