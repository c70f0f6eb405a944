// summary.json: the run's result (exit code, steps, conservation, cost) and where it came from
// (build and invocation), written with nlohmann::json and renamed into place whole.
#include <cmath>
#include <nlohmann/json.hpp>

#include "mpmshock/provenance.hpp"
#include "mpmshock/run_directory.hpp"
#include "mpmshock/time_loop.hpp"

namespace mpmshock {

namespace {

using Json = nlohmann::ordered_json;  // keys in the order written

// JSON has no NaN or infinity: null.
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json provenance_json() {
  const BuildInfo& b = build_info();
  const Invocation& inv = invocation();
  return Json{{"version", b.version},
              {"commit", b.commit},
              {"compiler", b.compiler},
              {"flags", b.flags},
              {"build_type", b.build_type},
              {"mpi", Comm::built_with_mpi()},
              {"command_line", inv.command_line},
              {"working_directory", inv.working_directory},
              {"host", inv.host},
              {"openmp_wait", inv.openmp_wait},
              {"started", inv.started},
              {"written", utc_now()}};
}

}  // namespace

void write_summary_json(const fs::path& path, const RunResult& r) {
  Json j;
  j["exit_code"] = r.exit_code;
  j["failure"] = r.failure;
  j["steps"] = r.steps;
  j["start_time"] = number(r.start_time);
  j["end_time"] = number(r.end_time);
  j["wall_seconds"] = number(r.wall_seconds);
  j["material_points"] = r.points;
  j["point_steps_per_second"] = number(r.point_steps_per_second);
  j["threads"] = r.threads;
  j["steps_with_fewer_threads"] = r.steps_with_fewer_threads;
  j["step_share"] = number(r.step_share);
  j["mass_error"] = number(r.mass_error);
  j["momentum_error"] = number(r.momentum_error);
  j["energy_error"] = number(r.energy_error);
  j["porosity"] = number(r.porosity);
  j["voids"] = r.voids;
  j["symmetry"] = r.symmetry;
  j["dimension"] = r.dimension;
  j["ranks"] = r.ranks;
  j["imbalance"] = number(r.imbalance);
  j["mpi_bytes_per_step"] = number(r.mpi_bytes_per_step);
  j["mpi_messages_per_step"] = number(r.mpi_messages_per_step);
  j["mpi_seconds"] = number(r.mpi_seconds);
  j["mpi_seconds_least"] = number(r.mpi_seconds_least);
  j["beyond_eos_fit"] = r.beyond_eos_fit;
  j["eos_fit_J"] = number(r.beyond_eos_fit_J);
  j["provenance"] = provenance_json();
  // A path or message that is not valid UTF-8 is written with U+FFFD rather than refused.
  const std::string text = j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";

  const fs::path tmp = path.string() + ".tmp";
  File f = open_output(tmp);
  std::fputs(text.c_str(), f.get());
  flush_or_throw(f.get(), path.string());
  f.reset();
  fs::rename(tmp, path);
}

}  // namespace mpmshock
