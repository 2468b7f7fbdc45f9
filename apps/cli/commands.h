// The subcommands of build/lpir-gseg, one file each (cmd_<name>.cpp). Each takes the arguments
// after its name, prints its own errors to stderr and returns the process exit code.
#pragma once

namespace lpir {

int RunSegment(int argc, char** argv);
int RunEvaluate(int argc, char** argv);
int RunSimulate(int argc, char** argv);
int RunCalibrate(int argc, char** argv);
int RunDemo(int argc, char** argv);
int RunDevices(int argc, char** argv);
int RunBench(int argc, char** argv);
int RunTopics(int argc, char** argv);

// The folder holding sensors/*.txt (next to the binary's sources, or $LPIR_SENSORS_DIR).
const char* SensorsDir();

}  // namespace lpir
