// vmt: the command line. Every subcommand has --help; errors go to stderr with the file and
// place of the fault; exit 0 = ok, 1 = the run or comparison failed, 2 = bad input.

#include <malloc.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>

#include "common/mapped_file.hpp"
#include "common/output_file.hpp"
#include "control/gateway/signal_table_format.hpp"
#include "control/nc/parser.hpp"
#include "render/image.hpp"
#include "render/image_compare.hpp"
#include "sim/cli/command_help.hpp"
#include "sim/cli/golden.hpp"
#include "sim/cli/option_checks.hpp"
#include "sim/cli/serve.hpp"
#include "sim/cli/stop_signals.hpp"
#include "sim/cli/study_slurm.hpp"
#include "sim/cli/view.hpp"
#include "sim/model/gateway_layout.hpp"
#include "sim/model/model_error.hpp"
#include "sim/runner/run_story.hpp"
#include "sim/runner/runner.hpp"
#include "sim/runner/scene_renderer.hpp"
#include "sim/study/case_replay.hpp"
#include "sim/study/study.hpp"
#include "sim/study/study_compare.hpp"
#include "sim/study/study_plan.hpp"

namespace {

using namespace vmt;
using sim::FiniteIn;
using sim::WholeIn;

int Run(const std::string& scene_path, const std::string& backend, double until,
        const std::string& out, const std::vector<std::string>& sets,
        const std::string& operator_file) {
  sim::Scene scene = sim::LoadScene(scene_path);
  for (const std::string& set : sets) {
    const size_t eq = set.find('=');
    const std::string error =
        eq == std::string::npos
            ? "expected NAME=VALUE"
            : sim::AddSignalPreset(scene.nc, set.substr(0, eq), set.substr(eq + 1));
    if (!error.empty()) {
      std::fprintf(stderr, "vmt: error: --set %s: %s\n", set.c_str(), error.c_str());
      return 2;
    }
  }
  sim::RunOptions options;
  if (backend == "physics") options.backend = sim::BackendKind::kPhysics;
  if (backend == "kinematic") options.backend = sim::BackendKind::kKinematic;
  if (until > 0) options.until_s = until;
  options.out_dir = out;
  if (!operator_file.empty()) options.operator_steps = sim::ReadOperatorSteps(operator_file);
  sim::CatchStopSignals();
  const sim::RunResult r = sim::RunScene(scene, options, sim::StopSignalName);
  std::printf("%s: %.3f s simulated in %.3f s (%.1fx real time), trace digest %s\n",
              scene.name.c_str(), r.simulated_s, r.wall_s,
              r.wall_s > 0 ? r.simulated_s / r.wall_s : 0.0, r.trace_digest.c_str());
  // Only a file the run wrote (events.jsonl may be a device: /dev/full reads zeros forever).
  if (std::filesystem::is_regular_file(out + "/events.jsonl")) {
    std::ifstream events(out + "/events.jsonl");
    for (const std::string& line : sim::RunStory(events)) std::printf("  %s\n", line.c_str());
  }
  std::printf("output: %s/{trace.csv,events.jsonl,summary.json}", out.c_str());
  for (const std::string& f : r.snapshot_files) std::printf(" %s", f.c_str());
  for (const std::string& f : r.contact_sheets) std::printf(" %s", f.c_str());
  const auto failed = std::count_if(r.expectations.begin(), r.expectations.end(),
                                    [](const auto& e) { return !e.passed; });
  std::printf("\nexpectations: %zu passed, %zu failed\n",
              r.expectations.size() - static_cast<size_t>(failed), static_cast<size_t>(failed));
  for (const std::string& f : r.failures) std::fprintf(stderr, "FAILED: %s\n", f.c_str());
  for (const std::string& e : r.write_errors) std::fprintf(stderr, "vmt: error: %s\n", e.c_str());
  if (!r.stop_reason.empty())
    std::fprintf(stderr, "vmt run: stopped early at %.4f s: %s\n", r.simulated_s,
                 r.stop_reason.c_str());
  if (!r.write_errors.empty()) return 2;
  if (!r.stop_reason.empty()) return sim::kStoppedEarly;
  return r.ok() ? 0 : 1;
}

int Snapshot(const std::string& scene_path, double at, const std::string& camera,
             const std::string& out, int width, int height) {
  sim::Scene scene = sim::LoadScene(scene_path);
  const sim::NamedCamera* cam = scene.Camera(camera);
  if (!cam) {
    std::string names;
    for (const auto& c : scene.cameras) names += " " + c.name;
    throw sim::ModelError(scene_path, "cameras", "no camera '" + camera + "' (have:" + names + ")");
  }
  // Run the scene up to `at` without writing its own outputs, then picture the machine there,
  // the workpiece as turned by then.
  sim::RunOptions options;
  options.until_s = at;
  options.snapshots = false;
  sim::SceneRun run(scene, options);
  while (!run.done()) run.Step();
  const sim::RunResult r = run.Finish();
  const sim::TurnedProfile turned{run.stock_cuts(), run.TurnedStockCylinders()};
  sim::SceneRenderer renderer(*scene.model, scene.workpiece);
  render::WritePng(out, renderer.Render(r.final_joint_positions, *cam, width, height,
                                        turned.version > 0 ? &turned : nullptr));
  std::printf("%s: %s at %.4f s -> %s\n", scene.name.c_str(), camera.c_str(), r.simulated_s,
              out.c_str());
  return 0;
}

// `vmt study repos`: the cases of the scene's `study:` plan into a study folder.
int StudyRepos(sim::study::StudyOptions options, const std::string& shard,
               const std::string& per_mille, const std::string& bench_json) {
  if (!shard.empty()) {
    const size_t slash = shard.find('/');
    try {
      size_t used = 0;
      options.shard = std::stoi(shard.substr(0, slash), &used);
      if (slash == std::string::npos || used != slash) throw std::invalid_argument(shard);
      options.shards = std::stoi(shard.substr(slash + 1), &used);
      if (used != shard.size() - slash - 1) throw std::invalid_argument(shard);
    } catch (const std::exception&) {
      std::fprintf(stderr, "vmt: error: --shard %s: expected K/N, e.g. 2/8\n", shard.c_str());
      return 2;
    }
  }
  if (!per_mille.empty()) {
    std::vector<int> points;
    std::stringstream ss(per_mille);
    for (std::string p; std::getline(ss, p, ',');) {
      try {
        size_t used = 0;
        points.push_back(std::stoi(p, &used));
        if (used != p.size()) throw std::invalid_argument(p);
      } catch (const std::exception&) {
        std::fprintf(stderr, "vmt: error: --per-mille %s: expected numbers 0..1000, e.g. 250,750\n",
                     per_mille.c_str());
        return 2;
      }
    }
    options.per_mille = points;
  }
  options.progress = options.progress && ::isatty(2);
  sim::CatchStopSignals();
  options.stop = sim::StopSignalName;
  const sim::study::StudySummary s = sim::study::RunStudy(options);
  if (!s.stopped.empty()) {
    if (s.cases == 0)
      std::fprintf(stderr,
                   "vmt study: stopped by %s during the reference run; %s holds %zu finished "
                   "cases; the same command again resumes the study\n",
                   s.stopped.c_str(), options.out_dir.c_str(), s.finished);
    else
      std::fprintf(stderr,
                   "vmt study: stopped by %s: %zu of %zu cases finished (%zu in this run), kept "
                   "in %s/cases.jsonl; the same command again resumes the study\n",
                   s.stopped.c_str(), s.finished, s.cases, s.run, options.out_dir.c_str());
    return sim::kStoppedEarly;
  }
  std::printf(
      "%s: %zu cases (%zu run, %zu already there) in %.2f s: %.0f cases/min with %d "
      "job(s)\n%s",
      options.out_dir.c_str(), s.cases, s.run, s.skipped, s.wall_s, s.cases_per_minute,
      options.jobs, s.text.c_str());
  std::printf("cases: %.1f s of CPU (%.3f s per case); %zu pictures in %.1f s\n", s.cases_cpu_s,
              s.run ? s.cases_cpu_s / s.run : 0.0, s.snapshots, s.snapshots_wall_s);
  std::printf("output: %s/{cases.jsonl,cases.csv,report.html}\n", options.out_dir.c_str());
  if (!bench_json.empty()) {
    std::filesystem::create_directories(std::filesystem::path(bench_json).parent_path().empty()
                                            ? std::filesystem::path(".")
                                            : std::filesystem::path(bench_json).parent_path());
    std::ostringstream out;
    out << "{\"benchmark\": \"study\", \"scene\": \"" << options.scene << "\", \"cases\": " << s.run
        << ", \"wall_s\": " << s.wall_s << ", \"cases_per_minute\": " << s.cases_per_minute
        << ", \"cases_cpu_s\": " << s.cases_cpu_s
        << ", \"cpu_s_per_case\": " << (s.run ? s.cases_cpu_s / s.run : 0.0)
        << ", \"snapshots\": " << s.snapshots << ", \"snapshots_wall_s\": " << s.snapshots_wall_s
        << ", \"jobs\": " << options.jobs << ", \"cores\": " << std::thread::hardware_concurrency()
        << "}\n";
    common::WriteFileAtomically(bench_json, out.str());
  }
  return 0;
}

int Check(const std::string& file, const std::string& dialect_name) {
  namespace nc = control::nc;
  std::string why;
  const std::optional<common::MappedFile> read = common::MappedFile::Read(file, &why);
  if (!read) {
    std::fprintf(stderr, "%s:0:0: error: cannot open file: %s\n", file.c_str(), why.c_str());
    return 2;
  }
  const std::string_view text = *read;
  const nc::Dialect dialect = dialect_name.empty()    ? nc::DetectDialect(text, file)
                              : dialect_name == "isg" ? nc::Dialect::kIsg
                                                      : nc::Dialect::kMtc200;
  const nc::ParseResult r = nc::ParseProgram(text, file, dialect);
  for (const nc::Diagnostic& d : r.errors)
    std::fprintf(stderr, "%s\n", nc::Format(d, r.program.files).c_str());
  std::printf("%s: %s, %zu blocks, %zu errors\n", file.c_str(), nc::ToString(dialect),
              r.program.blocks.size(), r.errors.size());
  return r.ok() ? 0 : 1;
}

int ImgDiff(const std::string& a, const std::string& b, const std::string& diff,
            int channel_tolerance, double tolerance_fraction) {
  const render::Image ia = render::ReadPng(a), ib = render::ReadPng(b);
  render::CompareOptions opt;
  opt.channel_tolerance = channel_tolerance;
  opt.allowed_fraction = tolerance_fraction;
  const render::CompareResult r = render::CompareImages(ia, ib, opt);
  std::printf("%s\n", render::DescribeComparison(ia, ib, r, opt).c_str());
  if (r.equal) return 0;
  if (!diff.empty() && !r.size_mismatch) {
    render::WritePng(diff, r.diff);
    std::printf("diff picture: %s\n", diff.c_str());
  }
  return 1;
}

/// A subcommand: its CLI11 node and what it does once the command line is parsed (2: bad input).
struct Command {
  CLI::App* app;
  std::function<int()> action;
};

Command AddRun(CLI::App& app) {
  struct Args {
    std::string scene, backend, out = "out", operator_file;
    double until = 0;
    std::vector<std::string> sets;
  };
  auto o = std::make_shared<Args>();
  CLI::App* run = app.add_subcommand(
      "run", "Run a scene; writes trace.csv, events.jsonl, summary.json and snapshots");
  run->add_option("scene", o->scene, "Scene file (YAML)")->required();
  run->add_option("--backend", o->backend, "physics or kinematic (default: the scene's)")
      ->check(CLI::IsMember({"physics", "kinematic"}));
  run->add_option("--until", o->until, "Stop at this simulated time, seconds")
      ->check(FiniteIn(sim::kDriveTickS, sim::kMaxSceneSeconds, "number of seconds"));
  run->add_option("--out", o->out, "Output folder")
      ->check(sim::kOutputFolder)
      ->capture_default_str();
  run->add_option("--set", o->sets,
                  "NAME=VALUE: a gateway signal the PLC writes, set at t = 0 (repeatable), e.g. "
                  "P00.mc_cmd_bs_type_w=4 P00.mc_cmd_bs_block_number_w=100");
  run->add_option("--operator", o->operator_file,
                  "operator.yaml of a vmt serve --http run: its keys and signals, taken at the "
                  "same ticks (the run repeats that one)");
  return {run,
          [o] { return Run(o->scene, o->backend, o->until, o->out, o->sets, o->operator_file); }};
}

Command AddSnapshot(CLI::App& app) {
  struct Args {
    std::string scene, camera = "iso", out;
    double at = 0;
    int width = 640, height = 480;
  };
  auto o = std::make_shared<Args>();
  CLI::App* snap = app.add_subcommand("snapshot", "Render the scene's machine at a time to a PNG");
  snap->add_option("scene", o->scene, "Scene file (YAML)")->required();
  snap->add_option("--at", o->at, "Simulated time, seconds")
      ->required()
      ->check(FiniteIn(0, sim::kMaxSceneSeconds, "number of seconds"));
  snap->add_option("--camera", o->camera, "Camera name (model or scene)")->capture_default_str();
  snap->add_option("--out", o->out, "PNG file to write")->required()->check(sim::kOutputFile);
  snap->add_option("--width", o->width, "Picture width")
      ->check(WholeIn(16, 4096))
      ->capture_default_str();
  snap->add_option("--height", o->height, "Picture height")
      ->check(WholeIn(16, 4096))
      ->capture_default_str();
  return {snap, [o] { return Snapshot(o->scene, o->at, o->camera, o->out, o->width, o->height); }};
}

Command AddCheck(CLI::App& app) {
  struct Args {
    std::string file, dialect;
  };
  auto o = std::make_shared<Args>();
  CLI::App* check = app.add_subcommand(
      "check", "Check an NC program: every error as file:line:column: error: text");
  check->add_option("file", o->file, "NC program file")->required();
  check->add_option("--dialect", o->dialect, "mtc200 or isg (default: from the file)")
      ->check(CLI::IsMember({"mtc200", "isg"}));
  return {check, [o] { return Check(o->file, o->dialect); }};
}

Command AddSignals(CLI::App& app) {
  struct Args {
    std::string model, format = "csv";
  };
  auto o = std::make_shared<Args>();
  CLI::App* signals = app.add_subcommand(
      "signals", "List the NC<->PLC signals and machine I/O of a model for the PLC engineer");
  signals->add_option("model", o->model, "Machine model (machine.yaml)")->required();
  signals->add_option("--format", o->format, "csv or json")
      ->check(CLI::IsMember({"csv", "json"}))
      ->capture_default_str();
  return {signals, [o] {
            const sim::MachineModel model = sim::LoadMachineModel(o->model);
            const auto table = control::gateway::BuildSignalTable(sim::GatewayLayoutOf(model));
            const std::string text = o->format == "json" ? control::gateway::FormatJson(table)
                                                         : control::gateway::FormatCsv(table);
            std::fwrite(text.data(), 1, text.size(), stdout);
            return 0;
          }};
}

Command AddServe(CLI::App& app) {
  struct Args {
    sim::ServeOptions options;
    bool realtime = false, lockstep = false;
  };
  auto o = std::make_shared<Args>();
  sim::ServeOptions& serve_options = o->options;
  CLI::App* serve = app.add_subcommand(
      "serve",
      "Run a scene live: its PLC outside over Modbus TCP, and/or the operator station in a "
      "browser (lockstep or real time)");
  serve->add_option("scene", serve_options.scene, "Scene file (YAML)")->required();
  CLI::Option* modbus =
      serve
          ->add_option("--modbus", serve_options.endpoint,
                       "HOST:PORT to serve the signals to an external PLC on (port 0: any); the "
                       "default without --http")
          ->capture_default_str();
  serve->add_option("--http", serve_options.http,
                    "HOST:PORT of the operator station, a web page to watch and operate the "
                    "machine (port 0: any); without --modbus the scene's PLC program runs");
  serve->add_option("--http-token", serve_options.http_token,
                    "Token every station request must carry (needed off loopback)");
  serve->add_flag("--lockstep", o->lockstep,
                  "The PLC steps the simulation a cycle at a time (default)");
  serve->add_flag("--realtime", o->realtime, "Run against the wall clock; report cycle lateness");
  serve->add_option("--until", serve_options.until_s, "Stop at this simulated time, seconds")
      ->check(FiniteIn(sim::kDriveTickS, sim::kMaxSceneSeconds, "number of seconds"));
  serve->add_option("--out", serve_options.out_dir, "Output folder")
      ->check(sim::kOutputFolder)
      ->capture_default_str();
  serve
      ->add_option("--plc-timeout", serve_options.plc_timeout_ms,
                   "Real time: ms without a write from the PLC after which the PLC link is "
                   "lost (its outputs drop, the NC stops with message 505); clients that only "
                   "read are monitors and do not keep it")
      ->check(FiniteIn(0.001, 3.6e6, "number of ms"))
      ->capture_default_str();
  serve
      ->add_flag("--wait-for-plc,!--no-wait-for-plc", serve_options.wait_for_plc,
                 "Real time: start the clock at the PLC's first write (default), or at once")
      ->capture_default_str();
  serve
      ->add_option("--idle-timeout", serve_options.idle_timeout_s,
                   "Lockstep: s of wall time without a cycle write after which serve stops "
                   "early (exit 3)")
      ->check(FiniteIn(0.001, 8.64e4, "number of seconds"))
      ->capture_default_str();
  serve
      ->add_option("--unit-id", serve_options.unit_id,
                   "Modbus unit id answered besides 0 and 255; others get exception 0B")
      ->check(WholeIn(1, 247))
      ->capture_default_str();
  serve
      ->add_option("--client-timeout", serve_options.client_timeout_s,
                   "s without a request after which a Modbus connection is closed (0: never)")
      ->check(FiniteIn(0, 8.64e4, "number of seconds"))
      ->capture_default_str();
  serve->add_flag("--allow-remote", serve_options.allow_remote,
                  "Let --modbus listen on an address other than loopback: clients on the "
                  "network may connect (a warning says so)");
  serve
      ->add_option("--allow-client", serve_options.allow_clients,
                   "With --allow-remote: a numeric address that may connect (repeatable); others "
                   "are closed at once, loopback always may")
      ->allow_extra_args(false);
  serve
      ->add_option("--late-limit", serve_options.late_limit_ms,
                   "Real time: ms after its time a cycle may start; a later one is recorded "
                   "(events.jsonl, serve.json) and fails the run (exit 1)")
      ->check(FiniteIn(0.001, 3.6e6, "number of ms"))
      ->capture_default_str();
  serve->add_flag("--allow-late", serve_options.allow_late,
                  "Real time: late cycles are recorded but do not fail the run");
  serve->footer(
      "Exit status: 0 the scene ended and passed, 1 it ended with failures (or, in real time, a "
      "cycle later than --late-limit), 2 bad input, 3 stopped early (lockstep idle timeout, "
      "SIGINT or SIGTERM); serve.json says why.");
  return {serve, [o, modbus] {
            o->options.modbus = modbus->count() > 0 || o->options.http.empty();
            if (o->realtime && o->lockstep) {
              std::fprintf(stderr, "vmt: error: --lockstep and --realtime exclude each other\n");
              return 2;
            }
            o->options.lockstep = !o->realtime;
            return sim::Serve(o->options);
          }};
}

Command AddView(CLI::App& app) {
  auto o = std::make_shared<sim::ViewOptions>();
  CLI::App* view = app.add_subcommand(
      "view",
      "Replay a finished run in the operator station: the machine, the NC screen, the "
      "events, a time slider");
  view->add_option("out", o->out_dir, "Output folder of vmt run or vmt serve")->required();
  view->add_option("--http", o->http, "HOST:PORT to serve the page on (port 0: any)")
      ->capture_default_str();
  view->add_option("--http-token", o->http_token,
                   "Token every request must carry (needed off loopback)");
  return {view, [o] { return sim::View(*o); }};
}

/// `vmt study compare DIR_A DIR_B`: two studies case by case.
Command AddStudyCompare(CLI::App& study) {
  struct Args {
    std::string a, b, html = "compare.html";
    double threshold = 0.1;
  };
  auto o = std::make_shared<Args>();
  CLI::App* compare = study.add_subcommand(
      "compare", "Two study folders side by side, case by case: what changed from A to B");
  compare->add_option("dir_a", o->a, "Study folder A (e.g. the old machine or program)")
      ->required();
  compare->add_option("dir_b", o->b, "Study folder B")->required();
  compare->add_option("--html", o->html, "Write the comparison page here")
      ->check(sim::kOutputFile)
      ->capture_default_str();
  compare->add_option("--threshold", o->threshold, "Report clearance changes larger than this, mm")
      ->check(FiniteIn(0, 1e6, "number of mm"))
      ->capture_default_str();
  return {compare, [o] {
            std::fputs(sim::study::CompareStudies(o->a, o->b, o->html, o->threshold).c_str(),
                       stdout);
            std::printf("output: %s\n", o->html.c_str());
            return 0;
          }};
}

/// `vmt study repos` and `vmt study merge`.
std::vector<Command> AddStudy(CLI::App& app) {
  struct Args {
    sim::study::StudyOptions options;
    std::string shard, per_mille, bench_json;
    double every_ms = 0;
    size_t max_cases = 0;
    bool no_fork = false;
    std::string run_ups = "memory";
    std::vector<std::string> merge_dirs;
    std::string merge_out;
    std::string replay_dir, replay_case;
    sim::ViewOptions replay_view;
    bool replay_serve = false;
  };
  auto o = std::make_shared<Args>();
  sim::study::StudyOptions& study_options = o->options;
  CLI::App* study = app.add_subcommand("study", "Collision studies of REPOS subroutines");
  study->require_subcommand(1);
  CLI::App* repos = study->add_subcommand(
      "repos",
      "Run the cases of a scene's study: plan (interruptions x retracts x modes x REPOS "
      "subroutines) on the kinematic backend with PathGuard");
  repos->add_option("scene", study_options.scene, "Scene file with a study: section")->required();
  repos->add_option("--out", study_options.out_dir, "Study folder (a rerun skips its cases)")
      ->required()
      ->check(sim::kOutputFolder);
  repos
      ->add_option("--jobs", study_options.jobs,
                   "Worker processes (1: the cases run in vmt's own process, without fork, unless "
                   "--run-ups fork)")
      ->check(WholeIn(1, 256))
      ->capture_default_str();
  repos->add_option("--shard", o->shard, "K/N: this process runs shard K of N (every N-th group)")
      ->check(sim::ShardOf(sim::study::kMaxShards));
  CLI::Option* every_ms =
      repos->add_option("--every-ms", o->every_ms, "Interrupt every T ms of the program's run")
          ->check(FiniteIn(sim::study::kMinEveryMs, sim::study::kMaxEveryMs, "number of ms"));
  repos
      ->add_option("--per-mille", o->per_mille,
                   "Interrupt every motion block at these points, e.g. 250,750")
      ->check(sim::WholeListIn(0, 1000, sim::study::kMaxPerMillePoints))
      ->excludes(every_ms);
  repos->add_option("--max-cases", o->max_cases, "Only the first N cases (of this shard)")
      ->check(WholeIn(1, 1000000000));
  CLI::Option* run_ups =
      repos
          ->add_option("--run-ups", o->run_ups,
                       "How the cases of an interruption share the run-up to it: memory (one "
                       "process going back to the run saved there), fork (a process each: "
                       "slower, a case that crashes does not end its worker), start (every case "
                       "from the program's start: slow, a check of the others)")
          ->check(CLI::IsMember({"fork", "memory", "start"}))
          ->capture_default_str();
  repos->add_flag("--no-fork", o->no_fork, "The same as --run-ups start")->excludes(run_ups);
  repos->add_option("--bench-json", o->bench_json, "Also write the speed here as JSON")
      ->check(sim::kOutputFile);
  repos
      ->add_option("--snapshots", study_options.snapshots,
                   "Pictures of the worst cases per subroutine: this many collisions and the "
                   "tightest clear case (0: none)")
      ->check(WholeIn(0, 100))
      ->capture_default_str();
  CLI::App* merge =
      study->add_subcommand("merge", "Join study folders (shards) into one, one result per case");
  merge->add_option("dirs", o->merge_dirs, "Study folders")->required();
  merge->add_option("--out", o->merge_out, "The joined study folder")
      ->required()
      ->check(sim::kOutputFolder);
  CLI::App* replay = study->add_subcommand(
      "replay", "Save one case's run in the study folder (cases/<id>/) to watch it with vmt view");
  replay->add_option("dir", o->replay_dir, "Study folder")->required();
  replay->add_option("case", o->replay_case, "Case id, as in cases.csv")->required();
  replay
      ->add_option("--http", o->replay_view.http,
                   "Also serve its replay on HOST:PORT (the operator station)")
      ->each([o](const std::string&) { o->replay_serve = true; });
  replay->add_option("--http-token", o->replay_view.http_token,
                     "Token every request must carry (needed off loopback)");
  Command run_replay{replay, [o] {
                       std::string folder;
                       try {
                         folder = sim::study::SaveCase(o->replay_dir, o->replay_case);
                       } catch (const sim::study::UnknownCase& e) {
                         std::fprintf(stderr, "vmt: error: %s\n", e.what());
                         return 2;
                       }
                       std::printf("case %s: %s/{trace.csv,events.jsonl,summary.json,case.json}\n",
                                   o->replay_case.c_str(), folder.c_str());
                       if (!o->replay_serve) {
                         std::printf("watch it: vmt view %s --http 127.0.0.1:8080\n",
                                     folder.c_str());
                         return 0;
                       }
                       std::fflush(stdout);
                       sim::ViewOptions view = o->replay_view;
                       view.out_dir = folder;
                       return sim::View(view);
                     }};
  Command run_repos{repos, [o] {
                      sim::study::StudyOptions options = o->options;
                      if (o->every_ms > 0) options.every_ms = o->every_ms;
                      if (o->max_cases > 0) options.max_cases = o->max_cases;
                      using sim::study::RunUpSharing;
                      options.run_ups = o->no_fork || o->run_ups == "start" ? RunUpSharing::kNone
                                        : o->run_ups == "memory"            ? RunUpSharing::kMemory
                                                                            : RunUpSharing::kFork;
                      options.progress = true;
                      return StudyRepos(options, o->shard, o->per_mille, o->bench_json);
                    }};
  Command run_merge{merge, [o] {
                      const size_t n = sim::study::MergeStudies(o->merge_dirs, o->merge_out);
                      std::printf("%s: %zu cases; output: %s/{cases.jsonl,cases.csv,report.html}\n",
                                  o->merge_out.c_str(), n, o->merge_out.c_str());
                      return 0;
                    }};
  std::vector<Command> commands = {run_repos, run_merge, run_replay, AddStudyCompare(*study)};
  for (auto& [sub, action] : sim::AddStudySlurmCommands(*study)) commands.push_back({sub, action});
  return commands;
}

Command AddImgdiff(CLI::App& app) {
  struct Args {
    std::string a, b, diff;
    double tolerance_fraction = render::kGoldenAllowedFraction;
    int channel_tolerance = render::kGoldenChannelTolerance;
  };
  auto o = std::make_shared<Args>();
  CLI::App* imgdiff = app.add_subcommand(
      "imgdiff", "Compare two PNG pictures: exit 0 equal, 1 different, 2 bad input");
  imgdiff->add_option("a", o->a, "First PNG")->required();
  imgdiff->add_option("b", o->b, "Second PNG")->required();
  imgdiff->add_option("--diff", o->diff, "Write a diff picture here when they differ")
      ->check(sim::kOutputFile);
  imgdiff
      ->add_option("--tolerance", o->channel_tolerance,
                   "Levels a channel may differ by before the pixel counts as different, "
                   "0..255 (the project's golden tolerance by default)")
      ->check(WholeIn(0, 255))
      ->capture_default_str();
  imgdiff
      ->add_option("--allowed-fraction", o->tolerance_fraction,
                   "Fraction of the pixels (0..1) allowed to differ (the project's golden "
                   "tolerance by default: 0.0005 = 0.05 %)")
      ->check(FiniteIn(0, 1, "fraction"))
      ->capture_default_str();
  return {imgdiff, [o] {
            return ImgDiff(o->a, o->b, o->diff, o->channel_tolerance, o->tolerance_fraction);
          }};
}

}  // namespace

int main(int argc, char** argv) {
  // Keep freed memory in the process instead of returning it to the kernel: first touches of
  // fresh pages cost ~20 us each on the project's VMs, and vmt allocates large program and
  // trace arenas repeatedly (studies, reloads).
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  // A file size limit (ulimit -f) is then a write error naming the file, as a full disk is,
  // instead of a kill that leaves the files cut.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"vmt: a virtual machine tool (CNC kernel + simulated lathe)"};
  app.require_subcommand(1);

  std::vector<Command> commands = {AddRun(app),     AddSnapshot(app), AddCheck(app),
                                   AddSignals(app), AddServe(app),    AddView(app)};
  for (Command& c : AddStudy(app)) commands.push_back(std::move(c));
  commands.push_back(AddImgdiff(app));
  for (auto& [sub, action] : sim::AddGoldenCommands(app)) commands.push_back({sub, action});
  sim::AddExamples(app);

  const sim::CommandWords words =
      sim::ReadCommandWords(app, std::vector<std::string>(argv + 1, argv + argc));
  if (!words.unknown.empty()) {
    std::string path = "vmt";
    for (const std::string& w : words.path) path += " " + w;
    std::fprintf(stderr, "%s: error: unknown command '%s'", path.c_str(), words.unknown.c_str());
    if (!words.suggestion.empty())
      std::fprintf(stderr, "; did you mean '%s'?", words.suggestion.c_str());
    std::fprintf(stderr, "\nRun %s --help for the commands.\n", path.c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    std::fprintf(stderr, "vmt: error: %s\nRun with --help for more information.\n", e.what());
    return 2;
  }
  try {
    for (const Command& c : commands)
      if (*c.app) return c.action();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vmt: error: %s\n", e.what());
    return 2;
  }
  return 2;
}
