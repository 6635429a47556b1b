// walkd: the kiosk daemon. `walkd --config kiosk.toml [--simulate SECONDS] [--output DIR] [--bundle PATH]`
// `walkd --config kiosk.toml --print-unit-dropin` prints the systemd drop-in for the configured devices.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/sinks/systemd_sink.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>

#include "firmware-host/daemon.hpp"
#include "firmware-host/stop_signal.hpp"
#include "firmware-host/unit_dropin.hpp"
#include "model/error.hpp"
#include "model/version.hpp"

namespace {

// Under systemd (stdout connected to the journal) log with priorities through sd_journal; else stderr.
void setup_logging() {
  if (std::getenv("JOURNAL_STREAM")) {
    auto sink = std::make_shared<spdlog::sinks::systemd_sink_mt>("walkd");
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("walkd", sink));
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace walk::kiosk;
  CLI::App app{"walkd: real-time building walkthrough kiosk"};
  app.set_version_flag("--version", std::string("walkd ") + walk::version());
  std::string config_path, output, bundle_path;
  double simulate = -1.0;
  bool print_dropin = false;
  app.add_option("--config,-c", config_path, "kiosk config (TOML)")->required();
  app.add_option("--simulate", simulate,
                 "run a simulated clock for SECONDS (trace devices, fixed frame rate)")
      ->check(CLI::PositiveNumber);
  app.add_option("--output,-o", output, "folder for summary.json and saved frames (overrides output.folder)");
  app.add_option("--bundle,-b", bundle_path, "compiled .walk bundle (overrides the config's bundle)");
  app.add_flag("--print-unit-dropin", print_dropin,
               "print the systemd drop-in (DeviceAllow, network) for the configured devices and exit");
  CLI11_PARSE(app, argc, argv);
  setup_logging();

  install_stop_handlers();
  auto load = [&] {
    KioskConfig config = load_kiosk_config(config_path);
    if (simulate > 0) config.simulation.seconds = simulate;
    if (!output.empty()) config.output.folder = output;
    if (!bundle_path.empty()) config.bundle = bundle_path;
    return config;
  };
  try {
    KioskConfig config = load();
    if (print_dropin) {
      std::fputs(unit_dropin(config).c_str(), stdout);
      return 0;
    }
    // Building 0 is the config's own bundle and start; next_building cycles through [[buildings]].
    std::vector<BuildingConfig> buildings{{config.bundle, config.start}};
    buildings.insert(buildings.end(), config.buildings.begin(), config.buildings.end());
    for (std::size_t b = 0;; b = (b + 1) % buildings.size()) {
      config.bundle = buildings[b].bundle;
      config.start = buildings[b].start;
      const auto bundle = walk::model::Bundle::open(config.bundle);
      auto renderer = make_gl_renderer(*bundle, config.display);
      spdlog::info("walkd: bundle {} ({} polygons, {} cells), renderer {}, {}", config.bundle,
                   bundle->polygons().size(), bundle->cells().size(), renderer->name(),
                   config.simulation.seconds > 0 ? fmt::format("simulated {:g} s", config.simulation.seconds)
                                                 : std::string("real time"));
      Daemon daemon(config, *bundle, *renderer, open_devices(config.devices));
      daemon.set_reloader(reload_flag(), load);
      const Summary s = daemon.run(stop_flag());
      if (s.stopped_by != "next_building") break;
      config = daemon.config();  // keeps reloads made during this building
    }
  } catch (const walk::Error& e) {
    spdlog::error("{}", e.what());
    return 1;
  } catch (const std::exception& e) {
    spdlog::error("unexpected: {}", e.what());
    return 2;
  }
  return 0;
}
