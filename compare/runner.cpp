// SPDX-License-Identifier: BSD-3-Clause
// Forked workers with a per-query time limit.
//
// Why processes: libccd's MPR loops have no iteration cap, so an
// FCL call may never return, and a thread stuck in one can neither be
// cancelled nor abandoned safely. Each work unit (a range of cases of one
// set) is evaluated in a child process that streams fixed-size messages
// through a pipe; before every FCL call it flushes a kStart message. If the
// parent sees a kStart that is not answered within the time limit, it kills
// the child, records a hang for that (case, method), and starts a new child
// that resumes the unit just after the hung query. Answers are a pure
// function of (set, index), so the statistics do not depend on the number
// of workers or on the scheduling; only the timings do.
#include "runner.h"

#include <fenv.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <limits>
#include <stdexcept>

#include "tricyl/triangle_cylinder.h"

namespace tricyl::compare {

namespace {

using Clock = std::chrono::steady_clock;
constexpr std::uint8_t kNoStage = 255;

enum MsgType : std::uint8_t {
  kBegin = 1,   // a case: oracle verdicts, tricyl's answer and stage
  kStart = 2,   // about to call an FCL method
  kResult = 3,  // a method's answer, ns per query, error size if wrong
  kDone = 4,    // the unit is complete
};

struct Msg {
  std::uint8_t type;
  std::uint8_t method;
  std::uint8_t answer;  // kResult: the answer; kBegin: tricyl's answer
  std::uint8_t truth;   // kBegin: bit 0 truth, bit 1 truth on float input,
                        // bit 2 the pose is improper (det R < 0)
  std::uint8_t stage;   // kBegin: tricyl's stage (kNoStage for meshes)
  std::uint8_t pad[3];
  std::uint32_t set;
  std::uint64_t index;
  double ns;
  double error_size;
  TriangleCounts tris;  // kBegin: .oracle; kResult (mesh_bvh): all three
};
static_assert(sizeof(Msg) <= 64, "messages must be small (atomic writes)");

struct Unit {
  std::size_t set;
  std::uint64_t begin, end;
  std::size_t first_method;  // > 0 when resuming after a hang
};

/// The methods run on the cases of `set`, in the run's order.
std::vector<Method> methodsFor(const CaseSet& set, const RunOptions& opt) {
  std::vector<Method> out;
  for (Method m : opt.methods)
    if (methodApplies(set, m)) out.push_back(m);
  return out;
}

/// Missed and extra triangles of a reported set against the oracle's
/// (sorted) set; duplicates in `got` count once.
TriangleCounts compareTriangles(const std::vector<std::uint32_t>& truth,
                                std::vector<std::uint32_t> got) {
  std::sort(got.begin(), got.end());
  got.erase(std::unique(got.begin(), got.end()), got.end());
  TriangleCounts t;
  t.oracle = std::uint32_t(truth.size());
  std::size_t i = 0, j = 0;
  while (i < truth.size() || j < got.size()) {
    if (j == got.size() || (i < truth.size() && truth[i] < got[j])) {
      ++t.missed;
      ++i;
    } else if (i == truth.size() || got[j] < truth[i]) {
      ++t.extra;
      ++j;
    } else {
      ++i;
      ++j;
    }
  }
  return t;
}

// ----------------------------------------------------------------- child

class Writer {
 public:
  explicit Writer(int fd) : fd_(fd) {}
  void put(const Msg& m) {
    if (n_ == kCap) flush();
    buf_[n_++] = m;
  }
  void flush() {
    const char* p = reinterpret_cast<const char*>(buf_);
    std::size_t left = n_ * sizeof(Msg);
    while (left > 0) {
      const ssize_t w = ::write(fd_, p, left);
      if (w < 0) {
        if (errno == EINTR) continue;
        _exit(3);
      }
      p += w;
      left -= std::size_t(w);
    }
    n_ = 0;
  }

 private:
  static constexpr std::size_t kCap = 64;
  int fd_;
  Msg buf_[kCap];
  std::size_t n_ = 0;
};

/// Optimisation barrier: the timed calls must not be merged or hoisted.
inline void clobber() { asm volatile("" : : : "memory"); }

/// ns per query. The first call gives the answer (and, if it never
/// returns, the hang); it is not timed into the statistic, because it pays
/// for whatever the previous method left in the caches. Then two timed
/// batches of repeated calls on the same input, each with enough
/// repetitions (2 .. 256) to last about 2 us, so that the clock's own cost
/// (~20 ns per reading) is a few percent at most; one repetition for calls
/// of 2 us or more. The result is the smaller batch time over the
/// repetitions: a warm-cache time from which a preemption or interrupt in
/// one batch is rejected (on a shared machine those cost milliseconds).
template <class Fn>
double timeQuery(Fn&& fn, bool* answer) {
  const auto t0 = Clock::now();
  *answer = fn();
  const auto t1 = Clock::now();
  const double first =
      std::chrono::duration<double, std::nano>(t1 - t0).count();
  const int reps = first >= 2000
                       ? 1
                       : int(std::clamp(std::ceil(2000 / std::max(first, 10.0)),
                                        2.0, 256.0));
  bool sink = false;
  double best = std::numeric_limits<double>::infinity();
  for (int batch = 0; batch < 2; ++batch) {
    const auto t2 = Clock::now();
    for (int r = 0; r < reps; ++r) {
      clobber();
      sink ^= fn();
    }
    const auto t3 = Clock::now();
    best = std::min(
        best, std::chrono::duration<double, std::nano>(t3 - t2).count() / reps);
  }
  volatile bool keep = sink;
  (void)keep;
  return best;
}

[[noreturn]] void childMain(const std::vector<CaseSet>& sets,
                            const RunOptions& opt, const Unit& unit, int fd) {
  signal(SIGPIPE, SIG_DFL);
  // FCL is measured as users run it: in the default floating-point
  // environment, even if the parent (a test) enabled FP traps.
  fedisableexcept(FE_ALL_EXCEPT);
  Writer out(fd);
  Evaluator ev;
  const CaseSet& set = sets[unit.set];
  const std::vector<Method> methods = methodsFor(set, opt);
  const bool want_float = std::find(opt.methods.begin(), opt.methods.end(),
                                    Method::kTricylFloat) != opt.methods.end();
  for (std::uint64_t i = unit.begin; i < unit.end; ++i) {
    const Case c = set.make(i);
    const Case fc = want_float ? roundToFloat(c) : c;
    const bool truth = oracleTruth(c);
    const bool truth_f = want_float ? oracleTruth(fc, true) : truth;
    const bool bvh = c.mesh && c.mesh_path == MeshPath::kBvh;
    const std::vector<std::uint32_t> oracle_tris =
        bvh ? oracleTriangles(c) : std::vector<std::uint32_t>{};
    Msg b{};
    b.type = kBegin;
    b.set = std::uint32_t(unit.set);
    b.index = i;
    b.truth = std::uint8_t((truth ? 1 : 0) | (truth_f ? 2 : 0) |
                           (isImproper(c.k.pose) ? 4 : 0));
    b.tris.oracle = std::uint32_t(oracle_tris.size());
    int stage = -1;
    b.answer = tricylDecide(c, &stage) ? 1 : 0;
    b.stage = stage < 0 ? kNoStage : std::uint8_t(stage);
    out.put(b);
    double size = -1, size_f = -1;  // error sizes, computed when needed
    const std::size_t first = i == unit.begin ? unit.first_method : 0;
    for (std::size_t p = first; p < methods.size(); ++p) {
      const Method m = methods[p];
      Msg r{};
      r.set = b.set;
      r.index = i;
      r.method = std::uint8_t(m);
      if (isFcl(m)) {
        r.type = kStart;
        out.put(r);
        out.flush();
      }
      bool answer = false;
      r.ns = timeQuery([&] { return ev.run(m, c); }, &answer);
      if (bvh) {  // the reported triangles (one more, untimed call)
        std::vector<std::uint32_t> got;
        ev.run(m, c, &got);
        r.tris = compareTriangles(oracle_tris, std::move(got));
      }
      r.type = kResult;
      r.answer = answer ? 1 : 0;
      const bool fl = usesFloatInput(m);
      if (answer != (fl ? truth_f : truth)) {
        double& s = fl ? size_f : size;
        if (s < 0) s = fl ? errorSize(fc, truth_f, true) : errorSize(c, truth);
        r.error_size = s;
      }
      out.put(r);
    }
  }
  Msg d{};
  d.type = kDone;
  d.set = std::uint32_t(unit.set);
  out.put(d);
  out.flush();
  _exit(0);
}

// ---------------------------------------------------------------- parent

struct Worker {
  pid_t pid = -1;
  int fd = -1;
  Unit unit{};
  std::vector<char> buf;
  bool start_pending = false;  // a kStart without its kResult
  Msg start{};
  Clock::time_point start_time;
  Clock::time_point last_msg;
  bool done = false;
  bool busy() const { return pid > 0; }
};

class Progress {
 public:
  Progress(std::uint64_t total, bool enabled)
      : total_(total),
        enabled_(enabled),
        tty_(isatty(2) != 0),
        t0_(Clock::now()) {}
  void update(std::uint64_t done, std::uint64_t hangs, bool final = false) {
    if (!enabled_) return;
    const auto now = Clock::now();
    const double el = std::chrono::duration<double>(now - t0_).count();
    if (el < 1.0 && !final) return;
    if (!final && now - last_ < std::chrono::milliseconds(tty_ ? 200 : 10000))
      return;
    if (final && !shown_) return;
    last_ = now;
    shown_ = true;
    const double frac = total_ ? double(done) / double(total_) : 1.0;
    const int width = 30;
    const int fill = int(frac * width);
    const double eta = frac > 0 ? el * (1 - frac) / frac : 0;
    std::fprintf(
        stderr,
        "%s[%.*s%*s] %5.1f%%  %llu/%llu cases  hangs %llu  "
        "%.0fs elapsed, ~%.0fs left%s",
        tty_ ? "\r" : "", fill, "==============================", width - fill,
        "", 100 * frac, (unsigned long long)done, (unsigned long long)total_,
        (unsigned long long)hangs, el, eta, tty_ && !final ? "" : "\n");
    std::fflush(stderr);
  }

 private:
  std::uint64_t total_;
  bool enabled_, tty_, shown_ = false;
  Clock::time_point t0_, last_;
};

void spawn(Worker& w, const std::vector<CaseSet>& sets, const RunOptions& opt,
           const Unit& unit) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe() failed");
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork() failed");
  if (pid == 0) {
    close(fds[0]);
    childMain(sets, opt, unit, fds[1]);
  }
  close(fds[1]);
  w.pid = pid;
  w.fd = fds[0];
  w.unit = unit;
  w.buf.clear();
  w.start_pending = false;
  w.done = false;
  w.last_msg = Clock::now();
}

void reap(Worker& w, bool kill_it) {
  if (kill_it) kill(w.pid, SIGKILL);
  int status = 0;
  waitpid(w.pid, &status, 0);
  close(w.fd);
  w.pid = -1;
  w.fd = -1;
}

}  // namespace

double mean(const std::vector<float>& v) {
  if (v.empty()) return kNaN;
  double sum = 0;
  for (float x : v) sum += double(x);
  return sum / double(v.size());
}

double percentile(std::vector<float>& v, double p) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const double rank = std::ceil(p / 100 * double(v.size()));
  const std::size_t i =
      std::size_t(std::clamp(rank, 1.0, double(v.size()))) - 1;
  return v[i];
}

RunResult runAll(const std::vector<CaseSet>& sets, const RunOptions& opt) {
  RunResult res;
  res.sets.resize(sets.size());
  const auto t0 = Clock::now();
  std::deque<Unit> queue;
  std::uint64_t total = 0;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    total += sets[s].count;
    for (std::uint64_t b = 0; b < sets[s].count; b += opt.unit)
      queue.push_back({s, b, std::min(sets[s].count, b + opt.unit), 0});
  }
  Progress progress(total, opt.progress);
  std::uint64_t begun = 0;
  std::vector<Worker> workers(std::size_t(std::max(1, opt.workers)));
  // Per-worker current case: tricyl's answer for the agreement matrix.
  std::vector<Msg> current(workers.size());
  std::vector<FeatureStats*> feature(workers.size(), nullptr);
  const auto timeout = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(opt.timeout_s));
  // A child that is silent this long outside an FCL call is broken.
  const auto stall =
      std::max(timeout * 10, Clock::duration(std::chrono::seconds(120)));

  auto handle = [&](std::size_t wi, const Msg& m) {
    Worker& w = workers[wi];
    w.last_msg = Clock::now();
    SetStats& st = res.sets[m.set];
    switch (m.type) {
      case kBegin: {
        // (Both are per worker slot; a resumed unit may land on another.)
        current[wi] = m;
        feature[wi] = &st.features[sets[m.set].make(m.index).k.feature];
        // A resumed unit repeats the kBegin of the case that hung.
        if (w.unit.first_method > 0 && m.index == w.unit.begin) break;
        ++feature[wi]->cases;
        ++begun;
        ++st.cases;
        st.hits += m.truth & 1;
        st.improper += (m.truth >> 2) & 1;
        if (m.stage < st.stage.size()) ++st.stage[m.stage];
        break;
      }
      case kStart:
        w.start_pending = true;
        w.start = m;
        w.start_time = w.last_msg;
        break;
      case kResult: {
        w.start_pending = false;
        const Method meth = Method(m.method);
        MethodStats& ms = st.method[m.method];
        const bool truth = usesFloatInput(meth) ? (current[wi].truth & 2)
                                                : (current[wi].truth & 1);
        ++ms.cases;
        // The largest error and the case attaining it (smallest index on
        // ties, so that the choice does not depend on scheduling).
        auto worst = [&](double* size, std::uint64_t* index) {
          if (*index == MethodStats::kNoCase || m.error_size > *size ||
              (m.error_size == *size && m.index < *index)) {
            *size = m.error_size;
            *index = m.index;
          }
        };
        if (m.answer && !truth) {
          ++ms.false_positives;
          worst(&ms.max_fp_size, &ms.worst_fp_index);
        } else if (!m.answer && truth) {
          ++ms.false_negatives;
          worst(&ms.max_fn_size, &ms.worst_fn_index);
        }
        if (bool(m.answer) != truth) ++feature[wi]->wrong[m.method];
        ++ms.agree[current[wi].answer][m.answer];
        ms.ns.push_back(float(m.ns));
        ms.tri_oracle += m.tris.oracle;
        ms.tri_missed += m.tris.missed;
        ms.tri_extra += m.tris.extra;
        break;
      }
      case kDone:
        w.done = true;
        break;
      default:
        throw std::runtime_error("tricyl-compare: corrupt worker message");
    }
  };

  while (true) {
    for (auto& w : workers)
      if (!w.busy() && !queue.empty()) {
        const Unit u = queue.front();
        queue.pop_front();
        spawn(w, sets, opt, u);
      }
    bool any = false;
    for (auto& w : workers) any |= w.busy();
    if (!any) break;

    std::vector<pollfd> pfds;
    std::vector<std::size_t> who;
    auto now = Clock::now();
    auto wait = std::chrono::milliseconds(200);
    for (std::size_t i = 0; i < workers.size(); ++i) {
      if (!workers[i].busy()) continue;
      pfds.push_back({workers[i].fd, POLLIN, 0});
      who.push_back(i);
      if (workers[i].start_pending) {
        const auto left = workers[i].start_time + timeout - now;
        wait = std::min(
            wait, std::chrono::duration_cast<std::chrono::milliseconds>(left) +
                      std::chrono::milliseconds(1));
      }
    }
    if (wait.count() < 0) wait = std::chrono::milliseconds(0);
    const int rc = poll(pfds.data(), pfds.size(), int(wait.count()));
    if (rc < 0 && errno != EINTR) throw std::runtime_error("poll() failed");
    for (std::size_t k = 0; k < pfds.size(); ++k) {
      if (!(pfds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      Worker& w = workers[who[k]];
      char tmp[1 << 14];
      const ssize_t n = read(w.fd, tmp, sizeof tmp);
      if (n > 0) {
        w.buf.insert(w.buf.end(), tmp, tmp + n);
        std::size_t off = 0;
        while (w.buf.size() - off >= sizeof(Msg)) {
          Msg m;
          std::memcpy(&m, w.buf.data() + off, sizeof m);
          off += sizeof m;
          handle(who[k], m);
        }
        w.buf.erase(w.buf.begin(), w.buf.begin() + long(off));
      } else if (n == 0) {  // EOF: the child has exited
        const bool ok = w.done;
        const Unit u = w.unit;
        if (!ok && w.start_pending) {
          // Died inside an FCL call: recorded like a hang (a query that
          // never answered), with a note on stderr.
          std::fprintf(stderr,
                       "\ntricyl-compare: %s crashed on set '%s' case %llu; "
                       "counted in hangs\n",
                       methodName(Method(w.start.method)),
                       sets[w.start.set].name.c_str(),
                       (unsigned long long)w.start.index);
          w.start_time = Clock::now() - timeout - timeout;
          continue;  // handled below as a timeout (kill is harmless)
        }
        reap(w, false);
        if (!ok)
          throw std::runtime_error(
              "tricyl-compare: a worker died in set '" + sets[u.set].name +
              "' cases " + std::to_string(u.begin) + ".." +
              std::to_string(u.end) + " (not a timeout: a crash)");
      }
    }
    now = Clock::now();
    for (std::size_t i = 0; i < workers.size(); ++i) {
      Worker& w = workers[i];
      if (!w.busy()) continue;
      if (w.start_pending && now - w.start_time > timeout) {
        const Msg s = w.start;
        const Unit u = w.unit;
        reap(w, true);
        ++res.worker_restarts;
        MethodStats& ms = res.sets[s.set].method[s.method];
        ++ms.cases;
        ++ms.hangs;
        ms.tri_oracle += current[i].tris.oracle;
        ms.tri_missed += current[i].tris.oracle;
        if (feature[i]) ++feature[i]->wrong[s.method];
        res.hangs.push_back({s.set, s.index, Method(s.method)});
        // Resume just after the hung query.
        const std::vector<Method> ms_set = methodsFor(sets[u.set], opt);
        std::size_t pos = 0;
        while (pos < ms_set.size() && ms_set[pos] != Method(s.method)) ++pos;
        Unit r{u.set, s.index, u.end, pos + 1};
        if (r.first_method >= ms_set.size()) {
          r.begin = s.index + 1;
          r.first_method = 0;
        }
        if (r.begin < r.end) queue.push_front(r);
      } else if (!w.start_pending && now - w.last_msg > stall) {
        const Unit u = w.unit;
        reap(w, true);
        throw std::runtime_error(
            "tricyl-compare: a worker stalled outside FCL in set '" +
            sets[u.set].name + "' cases " + std::to_string(u.begin) + "..");
      }
    }
    progress.update(begun, res.hangs.size());
  }
  progress.update(begun, res.hangs.size(), true);
  res.wall_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return res;
}

}  // namespace tricyl::compare
