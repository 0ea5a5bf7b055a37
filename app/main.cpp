// hotmesh: command line entry point.
#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  CLI::App app{"hotmesh: moves a CFD mesh onto the hot running geometry"};
  app.set_version_flag("--version", HOTMESH_VERSION);
  CLI11_PARSE(app, argc, argv);
  return 0;
}
