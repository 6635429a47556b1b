#pragma once
// The --plot of `walk bench` commands: the CSV beside the PNG, a gnuplot script drawing it, and gnuplot run
// on it (a failure is reported, the CSV stays).
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace walk::tools {

// The CSV's path for `png`: what the plot commands read.
inline std::string plot_data_path(const std::string& png) {
  return png + ".csv";
}

// Writes `csv` to plot_data_path(png) and `png`.gp (a 1000x600 PNG terminal, comma-separated data, then
// `commands`), and runs gnuplot on it.
inline void plot_with_gnuplot(const std::string& png, const std::string& csv, const std::string& commands) {
  const std::string data_path = plot_data_path(png);
  std::ofstream(data_path) << csv;
  const std::string script_path = png + ".gp";
  std::ofstream(script_path) << "set terminal pngcairo size 1000,600\nset output '" << png
                             << "'\nset datafile separator ','\n"
                             << commands;
  const std::string command = "gnuplot '" + script_path + "'";
  if (std::system(command.c_str()) != 0)
    std::fprintf(stderr, "gnuplot failed; the CSV is in %s\n", data_path.c_str());
}

}  // namespace walk::tools
