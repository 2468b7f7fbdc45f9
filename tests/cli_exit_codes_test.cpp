// The exit codes of every lpir-gseg command (apps/cli/exit_codes.h), run as a user runs them:
// a good run 0, some inputs failed 1, a bad command line 2, a refused result 3, an error that
// stops the command 4; each failure's reason on stderr, naming what was wrong. And `help`:
// `help COMMAND` prints exactly `COMMAND --help`, `help` the overview with the table.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "host/io/cloud_file.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

// What one run of the CLI gave.
struct Ran {
  int code = -1;
  std::string out, err;  // stdout, stderr
};

// Runs `lpir-gseg ARGS` with `env` (shell assignments, may be "") before it.
Ran Cli(const std::string& args, const std::string& env = "") {
  static int calls = 0;
  const std::string err_file = test::TempDir() + "/stderr" + std::to_string(calls++);
  Ran r;
  // (in braces: RunCommand's own 2>&1 then applies to the group, not to the CLI)
  r.code = test::RunCommand(
      "{ " + env + " " + test::CliPath() + " " + args + " 2>" + err_file + "; }", &r.out);
  r.err = test::ReadFileBytes(err_file);
  fs::remove_all(fs::path(err_file).parent_path());
  return r;
}

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// No Vulkan driver at all, wherever the tests run: the loader is pointed at a missing manifest.
const char kNoVulkan[] =
    "VK_ICD_FILENAMES=/nonexistent/icd.json VK_DRIVER_FILES=/nonexistent/icd.json";

// One simulated VLP-16 scan (dir/scan.bin, its truth dir/scan.label) and its predicted labels
// (dir/pred/scan.label), made once for all tests.
class CliExitCodes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::ScopedDir;
    const Ran sim = Cli("simulate --sensor vlp16 --seed 2 --out " + Dir() + "/scan.bin --labels " +
                        Dir() + "/scan.label");
    ASSERT_EQ(sim.code, 0) << sim.out << sim.err;
    const Ran seg = Cli("segment " + Dir() +
                        "/scan.bin --sensor vlp16 --backend cpu --quiet --out " + Dir() + "/pred");
    ASSERT_EQ(seg.code, 0) << seg.out << seg.err;
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string Dir() { return dir_->path; }
  static std::string Scan() { return Dir() + "/scan.bin"; }

  static test::ScopedDir* dir_;
};
test::ScopedDir* CliExitCodes::dir_ = nullptr;

TEST_F(CliExitCodes, TopLevel) {
  Ran r = Cli("");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "usage: lpir-gseg <command>")) << r.err;
  r = Cli("segmnet " + Scan());
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "unknown command 'segmnet'")) << r.err;
  r = Cli("--version");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(Has(r.out, "lpir-gseg ")) << r.out;
  r = Cli("--help");
  EXPECT_EQ(r.code, 0) << r.err;
  for (const char* line : {"0  done", "1  done, but some inputs failed", "2  usage", "3  refused",
                           "4  cannot run", "help [COMMAND|exit-codes]"})
    EXPECT_TRUE(Has(r.out, line)) << line << "\n" << r.out;
}

TEST_F(CliExitCodes, HelpCommandPrintsTheCommandsOwnHelp) {
  const Ran overview = Cli("--help");
  Ran r = Cli("help");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, overview.out);
  r = Cli("help exit-codes");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(Has(r.out, "4  cannot run")) << r.out;
  EXPECT_TRUE(Has(overview.out, r.out)) << "the overview holds the table";
  for (const char* command :
       {"segment", "evaluate", "simulate", "calibrate", "demo", "devices", "bench", "topics"}) {
    SCOPED_TRACE(command);
    const Ran own = Cli(std::string(command) + " --help");
    const Ran help = Cli(std::string("help ") + command);
    EXPECT_EQ(own.code, 0) << own.err;
    EXPECT_EQ(help.code, 0) << help.err;
    EXPECT_TRUE(Has(own.out, std::string("usage: lpir-gseg ") + command)) << own.out;
    EXPECT_EQ(help.out, own.out);
    EXPECT_EQ(own.out.find("{clouds}"), std::string::npos) << own.out;
    EXPECT_EQ(own.out.find("{writable clouds}"), std::string::npos) << own.out;
    EXPECT_TRUE(Has(own.out,
                    "exit codes: 0 done, 1 some inputs failed, 2 usage, 3 refused, "
                    "4 cannot run"))
        << own.out;
  }
  r = Cli("segment --help");
  EXPECT_TRUE(Has(r.out, "cloud files (" + CloudFormatList() + ")")) << r.out;
  EXPECT_TRUE(Has(r.out, "label (default), " + CloudFormatList(true) + ":")) << r.out;
  r = Cli("help segmnet");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "no command 'segmnet'")) << r.err;
  EXPECT_TRUE(Has(r.err, "segment")) << "lists the known ones: " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  r = Cli("help segment evaluate");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "give one command")) << r.err;
}

TEST_F(CliExitCodes, Segment) {
  const std::string out = " --out " + Dir() + "/seg";
  Ran r = Cli("segment " + Scan() + " --sensor vlp16 --backend cpu" + out);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(Dir() + "/seg/scan.label"));

  // Some inputs failed: each named, the rest written.
  fs::remove_all(Dir() + "/seg");
  r = Cli("segment " + Scan() + " " + Dir() + "/missing.bin --sensor vlp16 --backend cpu" + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(Has(r.err, Dir() + "/missing.bin")) << r.err;
  EXPECT_TRUE(Has(r.err, "1 of 2 files failed")) << r.err;
  EXPECT_TRUE(fs::exists(Dir() + "/seg/scan.label"));

  // The command line.
  r = Cli("segment " + Scan() + " --sensor vlp16 --bogus" + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "unknown option --bogus")) << r.err;
  EXPECT_TRUE(Has(r.err, "lpir-gseg help segment")) << r.err;
  r = Cli("segment " + Scan() + out + " --sensor");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "--sensor needs a value")) << r.err;
  r = Cli("segment " + Scan() + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "--sensor is required")) << r.err;
  r = Cli("segment " + Scan() + " --sensor vlp17" + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "unknown sensor profile 'vlp17'")) << r.err;
  r = Cli("segment " + Scan() + " --sensor vlp16 --backend gpu" + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "unknown backend 'gpu'")) << r.err;
  fs::create_directories(Dir() + "/empty");
  r = Cli("segment " + Dir() + "/empty --sensor vlp16" + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, Dir() + "/empty: folder holds no cloud files")) << r.err;

  // Cannot run: a profile file that does not parse, no Vulkan driver when Vulkan is asked for,
  // an output folder that cannot be made.
  std::ofstream(Dir() + "/bad_profile.txt") << "beams sixty-four\n";
  r = Cli("segment " + Scan() + " --sensor " + Dir() + "/bad_profile.txt" + out);
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, Dir() + "/bad_profile.txt")) << r.err;
  r = Cli("segment " + Scan() + " --sensor " + Dir() + "/missing_profile.txt" + out);
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, Dir() + "/missing_profile.txt: no such sensor profile file")) << r.err;
  r = Cli("segment " + Scan() + " --sensor vlp16 --backend vulkan" + out, kNoVulkan);
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, "the Vulkan backend could not be set up")) << r.err;
  r = Cli("segment " + Scan() + " --sensor vlp16 --backend cpu --out " + Scan() + "/labels");
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, Scan() + "/labels")) << r.err;
}

TEST_F(CliExitCodes, Evaluate) {
  const std::string pred = " --pred " + Dir() + "/pred";
  const std::string gt = " --gt " + Dir() + "/scan.label";
  Ran r = Cli("evaluate" + pred + gt + " --protocol dg");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(Has(r.out, "DG")) << r.out;

  r = Cli("evaluate" + pred + gt + " --protocol dg --bogus");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "unknown option --bogus")) << r.err;
  r = Cli("evaluate" + pred + gt + " --protocol kitti");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "unknown protocol 'kitti'")) << r.err;
  r = Cli("evaluate" + pred + gt);  // DG by default
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(Has(r.out, "DG")) << r.out;

  // Some predictions missing: named, the rest scored.
  fs::create_directories(Dir() + "/gt2");
  fs::copy_file(Dir() + "/scan.label", Dir() + "/gt2/scan.label");
  fs::copy_file(Dir() + "/scan.label", Dir() + "/gt2/other.label");
  r = Cli("evaluate" + pred + " --gt " + Dir() + "/gt2");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(Has(r.err, Dir() + "/pred/other.label")) << r.err;
  EXPECT_TRUE(Has(r.out, "scan ")) << r.out;

  r = Cli("evaluate --pred " + Dir() + "/nopred" + gt + " --protocol dg");
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, Dir() + "/nopred: no such prediction folder")) << r.err;
  r = Cli("evaluate" + pred + " --gt " + Dir() + "/missing.label --protocol dg");
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, Dir() + "/missing.label")) << r.err;
  fs::create_directories(Dir() + "/nopreds");
  r = Cli("evaluate --pred " + Dir() + "/nopreds" + gt + " --protocol dg");
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, "no prediction for ground truth " + Dir() + "/scan.label")) << r.err;
}

TEST_F(CliExitCodes, Simulate) {
  const std::string files = " --out " + Dir() + "/sim.bin --labels " + Dir() + "/sim.label";
  Ran r = Cli("simulate --sensor vlp16 --seed 5" + files);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(Dir() + "/sim.bin"));

  r = Cli("simulate --sensor vlp16" + files);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "--seed is required")) << r.err;
  r = Cli("simulate --sensor vlp16 --seed 5 --pitch 45" + files);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "--pitch must lie within [-30, 30] degrees")) << r.err;
  r = Cli("simulate --sensor hdl65 --seed 5" + files);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "unknown sensor profile 'hdl65'")) << r.err;

  r = Cli("simulate --sensor vlp16 --seed 5 --out " + Dir() + "/no/such/dir/sim.bin --labels " +
          Dir() + "/sim.label");
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, Dir() + "/no/such/dir/sim.bin")) << r.err;
}

TEST_F(CliExitCodes, Calibrate) {
  const std::string flat = Dir() + "/flat.bin";
  ASSERT_EQ(Cli("simulate --sensor vlp16 --seed 3 --scene flat --out " + flat + " --labels " +
                Dir() + "/flat.label")
                .code,
            0);
  Ran r = Cli("calibrate " + flat + " --sensor vlp16");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(Has(r.out, "accepted: pitch")) << r.out;

  // The street is no flat ground: refused, and no profile written.
  r = Cli("calibrate " + Scan() + " --sensor vlp16 --write-profile " + Dir() + "/p.txt");
  EXPECT_EQ(r.code, 3);
  EXPECT_TRUE(Has(r.err, "lpir-gseg calibrate: refused: ")) << r.err;
  EXPECT_FALSE(fs::exists(Dir() + "/p.txt"));

  r = Cli("calibrate --sensor vlp16");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "no scan given")) << r.err;
  r = Cli("calibrate " + flat + " --sensor vlp16 --max-b-diff -1");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "--max-b-diff must lie in (0, 1] m")) << r.err;

  r = Cli("calibrate " + Dir() + "/missing.bin --sensor vlp16");
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, Dir() + "/missing.bin")) << r.err;
}

TEST_F(CliExitCodes, Demo) {
  const std::string out = " --out " + Dir() + "/demo";
  Ran r = Cli("demo --backend cpu --runs 2" + out);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(Dir() + "/demo/demo_scan.label"));

  r = Cli("demo --runs 0" + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "--runs must be a whole number from 1 to 1000")) << r.err;
  r = Cli("demo --seed -1" + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "--seed")) << r.err;

  r = Cli("demo --backend vulkan --runs 1" + out, kNoVulkan);
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, "the Vulkan backend could not be set up")) << r.err;
  r = Cli("demo --backend cpu --runs 1 --out " + Scan() + "/demo");
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, Scan() + "/demo")) << r.err;
}

TEST_F(CliExitCodes, Devices) {
  Ran r = Cli("devices --all");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "unknown option --all")) << r.err;
  r = Cli("devices", kNoVulkan);
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, "lpir-gseg devices: no Vulkan device")) << r.err;
  LPIR_REQUIRE_VULKAN();
  r = Cli("devices");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(Has(r.out, "segment --backend vulkan without --device: ")) << r.out;
}

TEST_F(CliExitCodes, Bench) {
  Ran r = Cli("bench --runs 0");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "--runs, --scaling-runs and --frames must be at least 1")) << r.err;
  r = Cli("bench --bogus");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(Has(r.err, "unknown option --bogus")) << r.err;
  // A device asked for by name that cannot be had: no CPU-only report instead.
  r = Cli("bench --runs 1 --scaling-runs 1 --frames 1 --device 0 --data " + Dir() + "/none",
          kNoVulkan);
  EXPECT_EQ(r.code, 4);
  EXPECT_TRUE(Has(r.err, "--device 0: none (")) << r.err;
  // Without one, the CPU rows only, and success.
  r = Cli("bench --runs 1 --scaling-runs 1 --frames 1 --json --data " + Dir() + "/none", kNoVulkan);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(Has(r.out, "\"device\": \"none")) << r.out;
}

}  // namespace
}  // namespace lpir
