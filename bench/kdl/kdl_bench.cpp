// kdl_bench: times Orocos KDL's position IK solvers on a goal set written by
// `ikarus bench`, so that ikarus can be compared with a widely used library.
//
//   kdl_bench GOALFILE
//
// Output (stdout): a first line `kdl <version>`, then one line per solve:
//   <solver> <goal_index> <nanoseconds> <iterations> <return_code> <q_0> ... <q_{n-1}>
// all `lma` lines first, then all `nr_jl` lines (only for sets with joint
// limits). A file with a `paths` field is a path file: LMA only, each sample
// warm-started from the previous sample's answer. A rig goal file (first line
// `ikarus-rig-goals 1`) is solved by KDL's tree solver, one `tree` line per
// target set (kdl_bench_tree.inc). A malformed or unreadable goal file gives one
// line on stderr and exit status 2. See README.md next to this file for the details.

#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>
#include <kdl/config.h>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/segment.hpp>
#include <kdl/tree.hpp>
#include <kdl/treefksolverpos_recursive.hpp>
#include <kdl/treeiksolverpos_nr_jl.hpp>
#include <kdl/treeiksolvervel_wdls.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

// Version string of the KDL we were compiled against: the library's own macro
// when its config.h has one, else whatever the build script passed in.
#if defined(KDL_VERSION_STRING)
#define BENCH_KDL_VERSION KDL_VERSION_STRING
#elif defined(KDL_BENCH_PC_VERSION)
#define BENCH_KDL_VERSION KDL_BENCH_PC_VERSION
#else
#define BENCH_KDL_VERSION "1.5.1"
#endif

namespace {

// Joints whose limits are `nan nan` are given these bounds for NR_JL, which
// only ever clamps (never wraps): no iterate can get anywhere near them.
constexpr double kFreeJointMin = -1e9;
constexpr double kFreeJointMax = 1e9;

// Untimed warm-up solves per solver, over the first goals of the set.
constexpr std::size_t kWarmupGoals = 50;

// ---------------------------------------------------------------------------
// Goal file
// ---------------------------------------------------------------------------

struct Goal {
    double x, y, phi;
};

struct GoalSet {
    std::string name;
    std::size_t links = 0;
    double base_x = 0.0, base_y = 0.0;
    std::vector<double> lengths;
    std::vector<double> lim_min, lim_max;  // NaN for a free joint
    bool has_limits = false;               // true if any joint is limited
    std::vector<double> start;
    bool orientation = false;
    double tolerance = 0.0;
    double angle_tolerance = 0.0;  // read, but KDL has no separate angle tolerance
    unsigned max_iterations = 0;
    std::vector<Goal> goals;
    // Path mode: each path's sample count, in order (they sum to goals.size()); empty for a
    // goal set.
    std::vector<std::size_t> paths;
};

// Thrown on any problem with the goal file; main() prints it and exits 2.
struct FormatError {
    std::string message;
};

[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& field,
                       const std::string& what) {
    std::ostringstream os;
    os << path << ":" << line << ": field '" << field << "': " << what;
    throw FormatError{os.str()};
}

// Strict number parsing: the whole token must be a number. strtod accepts
// "nan" and "inf", which the limits field needs.
bool parse_double(const std::string& tok, double& out) {
    if (tok.empty()) return false;
    errno = 0;
    char* end = nullptr;
    out = std::strtod(tok.c_str(), &end);
    return end == tok.c_str() + tok.size() && errno != ERANGE;
}

bool parse_uint(const std::string& tok, unsigned long& out) {
    if (tok.empty() || tok[0] == '-' || tok[0] == '+') return false;
    errno = 0;
    char* end = nullptr;
    out = std::strtoul(tok.c_str(), &end, 10);
    return end == tok.c_str() + tok.size() && errno != ERANGE;
}

// One non-empty line of the file, comments stripped, split on whitespace.
struct Line {
    std::size_t number;
    std::vector<std::string> tokens;
};

std::vector<Line> read_lines(const std::string& path) {
    std::ifstream in(path);
    if (!in) {
        std::ostringstream os;
        os << path << ":0: field 'file': cannot open for reading";
        throw FormatError{os.str()};
    }
    std::vector<Line> lines;
    std::string text;
    std::size_t number = 0;
    while (std::getline(in, text)) {
        ++number;
        const auto hash = text.find('#');
        if (hash != std::string::npos) text.erase(hash);
        std::istringstream ss(text);
        Line line{number, {}};
        std::string tok;
        while (ss >> tok) line.tokens.push_back(tok);
        if (!line.tokens.empty()) lines.push_back(std::move(line));
    }
    if (in.bad()) {
        std::ostringstream os;
        os << path << ":" << number << ": field 'file': read error";
        throw FormatError{os.str()};
    }
    return lines;
}

GoalSet parse_goal_file(const std::string& path) {
    const std::vector<Line> lines = read_lines(path);
    GoalSet set;

    // Helpers that check a header line's value count and parse its numbers.
    auto expect_count = [&](const Line& l, std::size_t n) {
        const std::size_t got = l.tokens.size() - 1;
        if (got != n) {
            fail(path, l.number, l.tokens[0],
                 "expected " + std::to_string(n) + " value(s), got " + std::to_string(got));
        }
    };
    auto number_at = [&](const Line& l, std::size_t i) {
        double v;
        if (!parse_double(l.tokens[i], v)) {
            fail(path, l.number, l.tokens[0], "'" + l.tokens[i] + "' is not a number");
        }
        return v;
    };
    auto finite_at = [&](const Line& l, std::size_t i) {
        const double v = number_at(l, i);
        if (!std::isfinite(v)) fail(path, l.number, l.tokens[0], "value must be finite");
        return v;
    };
    auto uint_at = [&](const Line& l, std::size_t i) {
        unsigned long v;
        if (!parse_uint(l.tokens[i], v)) {
            fail(path, l.number, l.tokens[0],
                 "'" + l.tokens[i] + "' is not a non-negative integer");
        }
        return v;
    };
    // Per-joint fields need `links` to have been read already.
    auto need_links = [&](const Line& l) {
        if (set.links == 0) fail(path, l.number, l.tokens[0], "must come after 'links'");
    };

    if (lines.empty()) fail(path, 0, "ikarus-goals", "file is empty");
    {
        const Line& l = lines[0];
        if (l.tokens[0] != "ikarus-goals") {
            fail(path, l.number, "ikarus-goals",
                 "first line must be 'ikarus-goals 1', found '" + l.tokens[0] + "'");
        }
        expect_count(l, 1);
        if (l.tokens[1] != "1") {
            fail(path, l.number, "ikarus-goals", "unsupported version '" + l.tokens[1] + "'");
        }
    }

    std::map<std::string, std::size_t> seen;  // key -> line number, to reject duplicates
    std::size_t i = 1;
    for (; i < lines.size(); ++i) {
        const Line& l = lines[i];
        const std::string& key = l.tokens[0];
        if (seen.count(key)) {
            fail(path, l.number, key,
                 "duplicate (first on line " + std::to_string(seen[key]) + ")");
        }
        seen[key] = l.number;

        if (key == "name") {
            expect_count(l, 1);
            set.name = l.tokens[1];
        } else if (key == "links") {
            expect_count(l, 1);
            set.links = uint_at(l, 1);
            if (set.links == 0) fail(path, l.number, key, "must be at least 1");
        } else if (key == "base") {
            expect_count(l, 2);
            set.base_x = finite_at(l, 1);
            set.base_y = finite_at(l, 2);
        } else if (key == "lengths") {
            need_links(l);
            expect_count(l, set.links);
            for (std::size_t j = 0; j < set.links; ++j) set.lengths.push_back(finite_at(l, j + 1));
        } else if (key == "limits") {
            need_links(l);
            expect_count(l, 2 * set.links);
            for (std::size_t j = 0; j < set.links; ++j) {
                const double lo = number_at(l, 2 * j + 1);
                const double hi = number_at(l, 2 * j + 2);
                if (std::isnan(lo) != std::isnan(hi)) {
                    fail(path, l.number, key,
                         "joint " + std::to_string(j) + ": min and max must both be nan or both numbers");
                }
                if (!std::isnan(lo) && !(lo <= hi)) {
                    fail(path, l.number, key, "joint " + std::to_string(j) + ": min > max");
                }
                if (!std::isnan(lo)) set.has_limits = true;
                set.lim_min.push_back(lo);
                set.lim_max.push_back(hi);
            }
        } else if (key == "start") {
            need_links(l);
            expect_count(l, set.links);
            for (std::size_t j = 0; j < set.links; ++j) set.start.push_back(finite_at(l, j + 1));
        } else if (key == "orientation") {
            expect_count(l, 1);
            if (l.tokens[1] != "0" && l.tokens[1] != "1") fail(path, l.number, key, "must be 0 or 1");
            set.orientation = l.tokens[1] == "1";
        } else if (key == "tolerance") {
            expect_count(l, 1);
            set.tolerance = finite_at(l, 1);
            if (!(set.tolerance > 0)) fail(path, l.number, key, "must be positive");
        } else if (key == "angle_tolerance") {
            expect_count(l, 1);
            set.angle_tolerance = finite_at(l, 1);
        } else if (key == "max_iterations") {
            expect_count(l, 1);
            const unsigned long v = uint_at(l, 1);
            if (v == 0 || v > 100000000UL) fail(path, l.number, key, "must be in 1..1e8");
            set.max_iterations = static_cast<unsigned>(v);
        } else if (key == "paths") {
            if (l.tokens.size() < 2) fail(path, l.number, key, "expected at least 1 value, got 0");
            for (std::size_t j = 1; j < l.tokens.size(); ++j) {
                const unsigned long v = uint_at(l, j);
                if (v == 0) fail(path, l.number, key, "every path needs at least 1 sample");
                set.paths.push_back(v);
            }
        } else if (key == "goals") {
            break;  // goal lines follow
        } else {
            fail(path, l.number, key, "unknown field");
        }
    }

    // Every header field but name, base and angle_tolerance is required.
    const std::size_t header_end = i < lines.size() ? lines[i].number : lines.back().number;
    for (const char* key : {"links", "lengths", "limits", "start", "orientation", "tolerance",
                            "max_iterations", "goals"}) {
        if (std::string(key) == "goals" ? i == lines.size() : !seen.count(key)) {
            fail(path, header_end, key, "missing");
        }
    }

    const Line& header = lines[i];
    expect_count(header, 1);
    const unsigned long n_goals = uint_at(header, 1);
    if (lines.size() - i - 1 != n_goals) {
        const std::size_t where =
            lines.size() - i - 1 < n_goals ? lines.back().number : lines[i + 1 + n_goals].number;
        fail(path, where, "goals",
             "header says " + std::to_string(n_goals) + " goal line(s), file has " +
                 std::to_string(lines.size() - i - 1));
    }
    if (!set.paths.empty()) {
        std::size_t sum = 0;
        for (std::size_t v : set.paths) sum += v;
        if (sum != n_goals) {
            fail(path, header.number, "paths",
                 "sample counts sum to " + std::to_string(sum) + ", goals is " + std::to_string(n_goals));
        }
    }
    set.goals.reserve(n_goals);
    for (std::size_t g = i + 1; g < lines.size(); ++g) {
        const Line& l = lines[g];
        const std::string field = "goal " + std::to_string(g - i - 1);
        if (l.tokens.size() != 3) {
            fail(path, l.number, field,
                 "expected 3 numbers (x y phi), got " + std::to_string(l.tokens.size()));
        }
        double v[3];
        for (int k = 0; k < 3; ++k) {
            if (!parse_double(l.tokens[k], v[k]) || !std::isfinite(v[k])) {
                fail(path, l.number, field, "'" + l.tokens[k] + "' is not a finite number");
            }
        }
        set.goals.push_back({v[0], v[1], v[2]});
    }
    return set;
}

// ---------------------------------------------------------------------------
// KDL model and timing
// ---------------------------------------------------------------------------

// The planar chain: an optional fixed segment carrying the base offset, then
// one RotZ joint per link, each followed by a translation `length` along the
// joint frame's x axis. The tip frame of the last segment is the end effector.
KDL::Chain build_chain(const GoalSet& set) {
    KDL::Chain chain;
    if (set.base_x != 0.0 || set.base_y != 0.0) {
        chain.addSegment(
            KDL::Segment(KDL::Joint(KDL::Joint::None), KDL::Frame(KDL::Vector(set.base_x, set.base_y, 0.0))));
    }
    for (double length : set.lengths) {
        chain.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::RotZ), KDL::Frame(KDL::Vector(length, 0.0, 0.0))));
    }
    return chain;
}

// Target frame for a goal: position (x, y, 0), rotation RotZ(phi). For
// position-only sets LMA ignores the rotation through its weights; NR_JL
// cannot ignore it (see README.md).
KDL::Frame goal_frame(const Goal& g) {
    return KDL::Frame(KDL::Rotation::RotZ(g.phi), KDL::Vector(g.x, g.y, 0.0));
}

struct SolveRecord {
    long long nanoseconds;
    int iterations;  // -1 when the solver does not report it
    int return_code;
    std::vector<double> q;
};

// Solves every goal from the start pose with `solve(q_init, frame, q_out)` and
// `iterations()` (read right after each solve). Only the solve is timed. One
// untimed warm-up pass over the first goals comes first, so that caches,
// branch predictors and the CPU clock have settled.
template <class Solve, class Iterations>
std::vector<SolveRecord> run_solver(const GoalSet& set, const std::vector<KDL::Frame>& frames,
                                    Solve solve, Iterations iterations) {
    const std::size_t n = set.links;
    KDL::JntArray q_init(n);
    for (std::size_t j = 0; j < n; ++j) q_init(j) = set.start[j];
    KDL::JntArray q_out(n);

    const std::size_t warmup = std::min(kWarmupGoals, frames.size());
    for (std::size_t g = 0; g < warmup; ++g) solve(q_init, frames[g], q_out);

    std::vector<SolveRecord> records;
    records.reserve(frames.size());
    for (std::size_t g = 0; g < frames.size(); ++g) {
        const auto t0 = std::chrono::steady_clock::now();
        const int rc = solve(q_init, frames[g], q_out);
        const auto t1 = std::chrono::steady_clock::now();
        SolveRecord r;
        r.nanoseconds = std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count();
        r.iterations = iterations();
        r.return_code = rc;
        r.q.assign(q_out.data.data(), q_out.data.data() + n);
        records.push_back(std::move(r));
    }
    return records;
}

// Path mode: the first sample of each path is solved from the start pose, every later one
// from the previous sample's answer (a warm start, as a tracking user would do). Only the
// solve is timed. The untimed warm-up is a separate pass over the first samples.
template <class Solve, class Iterations>
std::vector<SolveRecord> run_paths(const GoalSet& set, const std::vector<KDL::Frame>& frames,
                                   Solve solve, Iterations iterations) {
    const std::size_t n = set.links;
    KDL::JntArray start(n);
    for (std::size_t j = 0; j < n; ++j) start(j) = set.start[j];
    KDL::JntArray q_init(n), q_out(n);

    q_init = start;
    const std::size_t warmup = std::min(kWarmupGoals, frames.size());
    for (std::size_t g = 0; g < warmup; ++g) {
        solve(q_init, frames[g], q_out);
        q_init = q_out;
    }

    std::vector<SolveRecord> records;
    records.reserve(frames.size());
    std::size_t g = 0;
    for (std::size_t samples : set.paths) {
        q_init = start;
        for (std::size_t k = 0; k < samples; ++k, ++g) {
            const auto t0 = std::chrono::steady_clock::now();
            const int rc = solve(q_init, frames[g], q_out);
            const auto t1 = std::chrono::steady_clock::now();
            SolveRecord r;
            r.nanoseconds = std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count();
            r.iterations = iterations();
            r.return_code = rc;
            r.q.assign(q_out.data.data(), q_out.data.data() + n);
            records.push_back(std::move(r));
            q_init = q_out;
        }
    }
    return records;
}

void print_records(const char* solver, const std::vector<SolveRecord>& records) {
    for (std::size_t g = 0; g < records.size(); ++g) {
        const SolveRecord& r = records[g];
        std::printf("%s %zu %lld %d %d", solver, g, r.nanoseconds, r.iterations, r.return_code);
        for (double q : r.q) std::printf(" %.17g", q);
        std::printf("\n");
    }
}

}  // namespace

#include "kdl_bench_tree.inc"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s GOALFILE\n", argv[0]);
        return 2;
    }
    try {
        if (is_rig_file(argv[1])) return run_rig(argv[1]);
    } catch (const FormatError& e) {
        std::fprintf(stderr, "kdl_bench: %s\n", e.message.c_str());
        return 2;
    }

    GoalSet set;
    try {
        set = parse_goal_file(argv[1]);
    } catch (const FormatError& e) {
        std::fprintf(stderr, "kdl_bench: %s\n", e.message.c_str());
        return 2;
    }

    const KDL::Chain chain = build_chain(set);
    std::vector<KDL::Frame> frames;
    frames.reserve(set.goals.size());
    for (const Goal& g : set.goals) frames.push_back(goal_frame(g));

    std::printf("kdl %s\n", BENCH_KDL_VERSION);

    // --- LMA: Levenberg-Marquardt on the weighted 6-D pose error. ----------
    // Task-space weights, in KDL's twist order (vx vy vz wx wy wz): only the
    // planar position, plus the rotation about z when orientation counts.
    // Joint limits are not supported by this solver and are ignored.
    {
        Eigen::Matrix<double, 6, 1> L;
        L << 1.0, 1.0, 0.0, 0.0, 0.0, set.orientation ? 1.0 : 0.0;
        // eps: stop when the weighted error norm is below the file's tolerance;
        // eps_joints: KDL's default (1e-15).
        KDL::ChainIkSolverPos_LMA lma(chain, L, set.tolerance, static_cast<int>(set.max_iterations));
        auto solve = [&](const KDL::JntArray& q0, const KDL::Frame& f, KDL::JntArray& q) {
            return lma.CartToJnt(q0, f, q);
        };
        auto iterations = [&] { return lma.lastNrOfIter; };
        const auto records =
            set.paths.empty() ? run_solver(set, frames, solve, iterations) : run_paths(set, frames, solve, iterations);
        print_records("lma", records);
    }

    // --- NR_JL: Newton-Raphson with a pseudo-inverse Jacobian, clamping to the
    // joint limits after every step. Only for goal sets that have limits (not in
    // path mode). ------------------------------------------------------------
    if (set.has_limits && set.paths.empty()) {
        KDL::JntArray q_min(set.links), q_max(set.links);
        for (std::size_t j = 0; j < set.links; ++j) {
            const bool free_joint = std::isnan(set.lim_min[j]);
            q_min(j) = free_joint ? kFreeJointMin : set.lim_min[j];
            q_max(j) = free_joint ? kFreeJointMax : set.lim_max[j];
        }
        KDL::ChainFkSolverPos_recursive fk(chain);
        KDL::ChainIkSolverVel_pinv vel(chain);  // KDL defaults: eps 1e-5, maxiter 150 (SVD)
        KDL::ChainIkSolverPos_NR_JL nr_jl(chain, q_min, q_max, fk, vel, set.max_iterations, set.tolerance);
        const auto records = run_solver(
            set, frames,
            [&](const KDL::JntArray& q0, const KDL::Frame& f, KDL::JntArray& q) { return nr_jl.CartToJnt(q0, f, q); },
            [] { return -1; });  // NR_JL does not report its iteration count
        print_records("nr_jl", records);
    }

    return std::fflush(stdout) == 0 ? 0 : 1;
}
