// drape_plies: the jobs of a laminate's plies, their surfaces loaded once per distinct mold,
// the drapes run by a pool of threads.

#include "job/laminate_run.hpp"

#include "commands/commands.hpp"

#include <plyfit/exporters/laminate.hpp>

#include <cmath>
#include <condition_variable>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

namespace plyfit::cli {

namespace {

// The keys that make a ply's surface: plies equal in these share one loaded surface.
std::string surface_signature(const DrapeJob& j) {
  std::ostringstream os;
  os.precision(17);
  os << j.mold << '\n'
     << j.face << '\n'
     << j.all_faces << '\n'
     << j.format << '\n'
     << j.flip_normal << '\n'
     << j.tolerance_rel << '\n'
     << j.max_iterations << '\n';
  for (int f : j.faces) os << f << ',';
  if (j.faces_at) os << '\n' << j.faces_at->transpose();
  return os.str();
}

void fail(PlyRun& r, const Error& e) {
  r.outcome.status = e.code == ErrorCode::kCancelled ? "cancelled" : "error";
  r.outcome.error = exporters::describe(e, ply_namer(r.ply));
  r.outcome.error_code = to_string(e.code);
  r.error_line = error_line(e, ply_namer(r.ply));
}

// Each ply's job; the plies whose keys are wrong fail here.
std::vector<PlyRun> make_jobs(const Laminate& laminate) {
  std::vector<PlyRun> runs;
  for (const auto& p : laminate.plies) {
    PlyRun r;
    r.ply = p;
    auto job = make_job(p.raw);
    if (job) {
      job->name_input = ply_namer(p);
      // Pieces are cut to fit the cut drawing's roll, which keeps a margin at each edge.
      if (job->roll_width) *job->roll_width *= 1.0 - 2.0 * exporters::kCutGapRel;
      r.job = std::move(job).value();
    } else {
      fail(r, job.error());
    }
    runs.push_back(std::move(r));
  }
  return runs;
}

// Each distinct surface loaded once (in stacking order of first use); its plies fail together
// when it cannot be loaded.
std::vector<std::shared_ptr<const LoadedSurface>> load_surfaces(std::vector<PlyRun>& runs) {
  std::map<std::string, std::shared_ptr<const LoadedSurface>> loaded;
  std::map<std::string, Error> failed;
  std::vector<std::shared_ptr<const LoadedSurface>> of_ply(runs.size());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (!runs[k].job) continue;
    const std::string sig = surface_signature(*runs[k].job);
    if (!loaded.count(sig) && !failed.count(sig)) {
      auto s = load_job_surface(*runs[k].job);
      if (s)
        loaded[sig] = std::make_shared<const LoadedSurface>(std::move(s).value());
      else
        failed.emplace(sig, s.error());
    }
    if (const auto f = failed.find(sig); f != failed.end())
      fail(runs[k], f->second);
    else
      of_ply[k] = loaded[sig];
  }
  return of_ply;
}

// Fibre directions (ply angles) closer than this mod 180 degrees are one direction, whose
// plies' seams are staggered.
constexpr double kSameFibreDeg = 0.5;

// The seams of the plies laid so far, for the stagger: a ply's seams keep apart from those of
// the plies of its fibre direction below it, so it waits for them (they were taken before it,
// and wait only for plies below them).
class SeamBoard {
 public:
  SeamBoard(const std::vector<PlyRun>& runs, double distance)
      : done_(runs.size(), false), seams_(runs.size()), distance_(distance) {
    for (const PlyRun& r : runs) angle_.push_back(r.job ? r.job->ply_angle_deg : 0.0);
  }
  // What ply k's seams keep apart from: the seams of the plies below it of its direction.
  SpliceStagger below(std::size_t k) {
    std::unique_lock<std::mutex> lock(mutex_);
    SpliceStagger st;
    st.distance = distance_;
    for (std::size_t j = 0; j < k; ++j) {
      if (std::abs(std::remainder(angle_[j] - angle_[k], 180.0)) > kSameFibreDeg) continue;
      changed_.wait(lock, [&] { return done_[j]; });
      st.seams.insert(st.seams.end(), seams_[j].begin(), seams_[j].end());
    }
    return st;
  }
  // Ply k is done (whatever became of it): its seams, if it was split.
  void publish(std::size_t k, const PlyRun& r) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (r.outcome.splices)
        for (const Seam& s : r.outcome.splices->seams)
          for (const auto& line : s.polylines) seams_[k].push_back(line);
      done_[k] = true;
    }
    changed_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<bool> done_;
  std::vector<std::vector<std::vector<Vec3>>> seams_;
  std::vector<double> angle_;
  double distance_;
};

// One ply's drape; an exception (a bug) fails the ply, not the laminate.
void drape_one(PlyRun& r, const LoadedSurface& surface, const std::atomic<bool>* cancel) {
  r.ran = true;
  try {
    auto out = run_job_on(*r.job, surface, cancel);
    if (out)
      r.outcome = std::move(out).value();
    else
      fail(r, out.error());
  } catch (const std::exception& e) {
    fail(r, Error{ErrorCode::kPlyException, "", {std::string(e.what())}});
  }
}

}  // namespace

exporters::InputNamer ply_namer(const LaminatePly& ply) {
  const exporters::InputNamer keys = input_namer(ply.raw, drape_options());
  const std::string angle = origin_of(ply.raw, "ply-angle") + ": key 'angle'";
  return [keys, angle](const std::string& input) {
    return input == "ply-angle" ? angle : keys(input);
  };
}

std::vector<PlyRun> drape_plies(const Laminate& laminate, int jobs, const std::atomic<bool>* cancel,
                                const std::function<void(const PlyRun&)>& on_done) {
  std::vector<PlyRun> runs = make_jobs(laminate);
  const auto surfaces = load_surfaces(runs);
  SeamBoard board(runs, laminate.splice_stagger);
  if (laminate.splice_stagger > 0.0)
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (runs[k].job && runs[k].job->roll_width)
        runs[k].job->stagger = [&board, k] { return board.below(k); };
  std::mutex done_mutex;
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t k = next++; k < runs.size(); k = next++) {
      if (surfaces[k] && !(cancel && cancel->load())) drape_one(runs[k], *surfaces[k], cancel);
      if (!runs[k].ran && surfaces[k]) runs[k].outcome.status = "cancelled";
      board.publish(k, runs[k]);
      const std::lock_guard<std::mutex> lock(done_mutex);
      if (on_done) on_done(runs[k]);
    }
  };
  std::vector<std::thread> pool;
  const auto n = std::min<std::size_t>(static_cast<std::size_t>(std::max(jobs, 1)), runs.size());
  for (std::size_t t = 0; t < n; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  return runs;
}

}  // namespace plyfit::cli
