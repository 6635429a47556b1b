// walkd: the kiosk daemon. `walkd --config kiosk.toml [--simulate SECONDS] [--output DIR] [--bundle PATH]`
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>

#include "firmware-host/daemon.hpp"
#include "firmware-host/stop_signal.hpp"
#include "model/error.hpp"

int main(int argc, char** argv) {
  using namespace walk::kiosk;
  CLI::App app{"walkd: real-time building walkthrough kiosk"};
  std::string config_path, output, bundle_path;
  double simulate = -1.0;
  app.add_option("--config,-c", config_path, "kiosk config (TOML)")->required();
  app.add_option("--simulate", simulate,
                 "run a simulated clock for SECONDS (trace devices, fixed frame rate)")
      ->check(CLI::PositiveNumber);
  app.add_option("--output,-o", output, "folder for summary.json and saved frames (overrides output.folder)");
  app.add_option("--bundle,-b", bundle_path, "compiled .walk bundle (overrides the config's bundle)");
  CLI11_PARSE(app, argc, argv);

  install_stop_handlers();
  try {
    KioskConfig config = load_kiosk_config(config_path);
    if (simulate > 0) config.simulation.seconds = simulate;
    if (!output.empty()) config.output.folder = output;
    if (!bundle_path.empty()) config.bundle = bundle_path;

    const auto bundle = walk::model::Bundle::open(config.bundle);
    auto renderer = make_gl_renderer(*bundle, config.display);
    spdlog::info("walkd: bundle {} ({} polygons, {} cells), renderer {}, {}", config.bundle,
                 bundle->polygons().size(), bundle->cells().size(), renderer->name(),
                 config.simulation.seconds > 0 ? fmt::format("simulated {:g} s", config.simulation.seconds)
                                               : std::string("real time"));
    Daemon daemon(config, *bundle, *renderer, open_devices(config.devices));
    daemon.run(stop_flag());
  } catch (const walk::Error& e) {
    spdlog::error("{}", e.what());
    return 1;
  } catch (const std::exception& e) {
    spdlog::error("unexpected: {}", e.what());
    return 2;
  }
  return 0;
}
