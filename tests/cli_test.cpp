// The horizon command line: every subcommand, and every error path's exit status and message.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace {

namespace fs = std::filesystem;

struct Result {
  int status;
  std::string output;  // stdout and stderr together
};

class CliTest : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("horizon_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  Result run(const std::string& arguments) const {
    const std::string command = "cd " + dir_.string() + " && " HORIZON_CLI " " + arguments + " 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    Result result{-1, {}};
    std::array<char, 4096> buffer;
    while (std::size_t got = std::fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), got);
    const int status = ::pclose(pipe);
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
  }
  void write(const std::string& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }
  bool exists(const std::string& name) const { return fs::exists(dir_ / name); }
  /// The command exits 2 with one clear message containing `message`.
  void expect_refused(const std::string& arguments, const std::string& message) const {
    const Result result = run(arguments);
    EXPECT_EQ(result.status, 2) << arguments << "\n" << result.output;
    EXPECT_NE(result.output.find(message), std::string::npos) << arguments << "\n" << result.output;
  }

  fs::path dir_;
};

#define EXPECT_OUTPUT(result, text) \
  EXPECT_NE((result).output.find(text), std::string::npos) << (result).output

TEST_F(CliTest, GenerateSearchVerify) {
  ASSERT_EQ(run("generate lattice --n 12 --out lat.npy").status, 0);
  ASSERT_EQ(run("generate random --count 3000 --seed 4 --out rnd.txt").status, 0);
  ASSERT_EQ(run("generate clusters --count 3000 --clusters 5 --sigma 0.3 --dims 2 --out clu.xyz").status, 0);

  const Result search = run("search lat.npy --horizon 1.25 --backend serial --out lat --json");
  ASSERT_EQ(search.status, 0) << search.output;
  // 12^3 lattice, h = 10/12, m = 1.5: closed form sum over |v| < 1.5 of prod (12 - |v_d|).
  EXPECT_OUTPUT(search, "\"neighbors\":26928");
  for (const char* key : {"\"points\":1728", "\"dims\":3", "\"backend\":\"serial\"", "\"threads\":1",
                          "\"grid\":", "\"search\":", "\"write\":", "\"total\":", "\"points_per_second\":"})
    EXPECT_OUTPUT(search, key);
  EXPECT_TRUE(exists("lat.offsets.npy") && exists("lat.indices.npy"));
  EXPECT_EQ(run("verify lat.npy lat --horizon 1.25").status, 0);

  ASSERT_EQ(run("search rnd.txt --horizon 0.9 --backend openmp --threads 2 --metric l1 --cells-per-horizon 2 --half --out rnd --format csv").status, 0);
  EXPECT_TRUE(exists("rnd.csv"));
  const Result ok = run("verify rnd.txt rnd --horizon 0.9 --metric l1 --half");
  EXPECT_EQ(ok.status, 0) << ok.output;
  EXPECT_OUTPUT(ok, "OK: all 3000 rows (exact)");

  ASSERT_EQ(run("search clu.xyz --horizon 0.2 --metric linf --out clu").status, 0);
  EXPECT_EQ(run("verify clu.xyz clu --horizon 0.2 --metric linf").status, 0);
  // A list checked against the wrong horizon differs from the oracle: exit 1.
  const Result wrong = run("verify clu.xyz clu --horizon 0.21 --metric linf");
  EXPECT_EQ(wrong.status, 1) << wrong.output;
  EXPECT_OUTPUT(wrong, "MISMATCH row");
}

TEST_F(CliTest, VerifySamplesLargeInputs) {
  ASSERT_EQ(run("generate random --count 30000 --out big.npy").status, 0);
  ASSERT_EQ(run("search big.npy --horizon 0.5 --out big --quiet").status, 0);
  const Result ok = run("verify big.npy big --horizon 0.5 --sample 500");
  EXPECT_EQ(ok.status, 0) << ok.output;
  EXPECT_OUTPUT(ok, "500 sampled rows of 30000");
}

TEST_F(CliTest, BuiltInLatticeAndEmptyInput) {
  const Result lattice = run("search lattice:10 --horizon 1.5");
  EXPECT_EQ(lattice.status, 0) << lattice.output;
  EXPECT_OUTPUT(lattice, "1000 points (3-D)");
  write("empty.csv", "# nothing\n");
  const Result empty = run("search empty.csv --horizon 1 --out e --json");
  EXPECT_EQ(empty.status, 0) << empty.output;
  EXPECT_OUTPUT(empty, "\"neighbors\":0");
  EXPECT_TRUE(exists("e.offsets.npy"));
}

TEST_F(CliTest, BadInputExitsTwoWithOneClearMessage) {
  write("nan.csv", "0 0 0\n1 nan 2\n");
  write("ragged.csv", "0 0 0\n1 2\n");
  write("words.csv", "0 0 0\n1 two 3\n");
  write("good.csv", "0 0 0\n1 1 1\n");
  const std::pair<std::string, std::string> cases[] = {
      {"search nan.csv --horizon 1", "nan.csv:2: non-finite coordinate"},
      {"search ragged.csv --horizon 1", "ragged.csv:2: expected 3 columns, found 2"},
      {"search words.csv --horizon 1", "words.csv:2: 'two' is not a number"},
      {"search missing.npy --horizon 1", "missing.npy: cannot open"},
      {"search good.csv --horizon 0", "horizon must be finite and > 0"},
      {"search good.csv --horizon -2", "horizon must be finite and > 0"},
      {"search good.csv --horizon nan", "horizon must be finite and > 0"},
      {"search good.csv --horizon 1 --out nowhere/list", "output directory 'nowhere' does not exist"},
      {"search good.csv --horizon 1 --cells-per-horizon 4", "cells-per-horizon"},
      {"search good.csv", "--horizon D or --radii FILE is required"},
      {"search good.csv --horizon 1 --backend gpu", "backend"},
      {"verify good.csv missing --horizon 1", "missing.offsets.npy: cannot open"},
      {"search lattice:0 --horizon 1", "expected lattice:N"},
  };
  for (const auto& [arguments, message] : cases) expect_refused(arguments, message);
  EXPECT_FALSE(exists("nowhere"));
}

TEST_F(CliTest, FailedWriteLeavesNoFileThatLooksValid) {
  write("good.csv", "0 0 0\n1 1 1\n");
  fs::create_directory(dir_ / "locked");
  fs::permissions(dir_ / "locked", fs::perms::owner_read | fs::perms::owner_exec);
  const Result result = run("search good.csv --horizon 2 --out locked/list");
  if (::geteuid() != 0) {  // root ignores permissions
    EXPECT_EQ(result.status, 2) << result.output;
    EXPECT_OUTPUT(result, "locked/list");
  }
  for (const auto& entry : fs::directory_iterator(dir_ / "locked"))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  fs::permissions(dir_ / "locked", fs::perms::owner_all);
}

TEST_F(CliTest, GpusOptionIsCheckedAndUsed) {
  expect_refused("search lattice:5 --horizon 2.5 --gpus 0,x", "expected all, a count, or a list");
  expect_refused("search lattice:5 --horizon 2.5 --backend cuda --gpus 64", "does not exist");
  const Result cpu = run("search lattice:5 --horizon 2.5 --backend serial --gpus 1");
  EXPECT_EQ(cpu.status, 2);
  if (cpu.output.find("does not exist (0 visible)") == std::string::npos)  // a machine with a GPU
    EXPECT_OUTPUT(cpu, "devices are for the cuda backend");
}

// A run killed while it writes the list leaves no file that looks like a complete list (the
// offsets, renamed into place last, are absent), and a rerun succeeds.
TEST_F(CliTest, KilledWriteLeavesNoListThatLooksValid) {
  for (int signal : {SIGTERM, SIGKILL}) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      if (::chdir(dir_.c_str()) != 0) ::_exit(127);
      ::execl(HORIZON_CLI, HORIZON_CLI, "search", "lattice:110", "--horizon", "0.2741", "--out", "big", "--quiet",
              static_cast<char*>(nullptr));
      ::_exit(127);
    }
    bool writing = false;
    for (int wait = 0; wait < 6000 && !writing; ++wait) {  // up to 30 s for the write to start
      for (const auto& entry : fs::directory_iterator(dir_))
        if (entry.path().filename().string().find(".tmp") != std::string::npos) writing = true;
      if (!writing) ::usleep(5000);
    }
    ASSERT_TRUE(writing) << "the write never started";
    ::kill(pid, signal);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) continue;  // the write won the race
    EXPECT_FALSE(exists("big.offsets.npy")) << "signal " << signal;
    // A rerun writes over what the killed one left (a small list: the write is what is tested).
    const Result rerun = run("search lattice:20 --horizon 1.5 --out big --quiet");
    EXPECT_EQ(rerun.status, 0) << rerun.output;
    EXPECT_TRUE(exists("big.offsets.npy") && exists("big.indices.npy"));
    fs::remove(dir_ / "big.offsets.npy");
    fs::remove(dir_ / "big.indices.npy");
  }
}

TEST_F(CliTest, VtkOutputAndItsRefusals) {
  const Result written = run("search lattice:6 --horizon 2.5 --vtk cloud.vtu --vtk-bonds --json");
  ASSERT_EQ(written.status, 0) << written.output;
  EXPECT_OUTPUT(written, "cloud.vtu");
  std::ifstream file(dir_ / "cloud.vtu", std::ios::binary);
  std::string head(300, '\0');
  file.read(head.data(), static_cast<std::streamsize>(head.size()));
  EXPECT_NE(head.find("<VTKFile type=\"UnstructuredGrid\""), std::string::npos) << head;
  // 216 vertex cells and the 6^3 lattice's 1,440 pairs at m = 1.5 (2,880 entries / 2).
  EXPECT_NE(head.find("NumberOfPoints=\"216\" NumberOfCells=\"1656\""), std::string::npos) << head;
  expect_refused("search lattice:6 --horizon 2.5 --vtk-bonds", "--vtk-bonds needs --vtk");
  expect_refused("search lattice:6 --horizon 2.5 --vtk missing/cloud.vtu", "does not exist");
  // lattice 60 at m = 3.015: 1.3e7 pairs, more than --vtk-bonds draws; nothing is left behind.
  expect_refused("search lattice:60 --horizon 0.5025 --vtk big.vtu --vtk-bonds", "bonds are more than");
  EXPECT_FALSE(exists("big.vtu"));
}

TEST_F(CliTest, BondFiltersCutBondsAndBadFiltersAreNamed) {
  // A disk in the plane x = 5 of the 12^3 lattice (spacing 10/12) cuts the x-bonds through it.
  write("disk.json", R"([{"type": "disk", "center": [5, 5, 5], "normal": [1, 0, 0], "radius": 2}])");
  const Result cut = run("search lattice:12 --horizon 1.25 --bond-filters disk.json --json --out cut");
  ASSERT_EQ(cut.status, 0) << cut.output;
  EXPECT_OUTPUT(cut, "\"bond_filters\":1");
  EXPECT_EQ(cut.output.find("\"bonds_cut\":0,"), std::string::npos) << cut.output;
  write("bad.json", R"([{"type": "disk", "center": [5, 5, 5], "radius": 2}])");
  expect_refused("search lattice:12 --horizon 1.25 --bond-filters bad.json", "bad.json: filter 0: missing key 'normal'");
  expect_refused("search lattice:12 --horizon 1.25 --bond-filters none.json", "none.json");
  expect_refused("search lattice:12 --horizon 1.25 --box 10,10,10 --bond-filters disk.json", "--bond-filters with --box");
}

TEST_F(CliTest, BlockPairsKeepOnlyTheirBonds) {
  // Two rows of points (Peridigm: x y z block volume), block 1 at y = 0 and block 2 at y = 1:
  // with pairs 1-1 and 2-2 no bond crosses between the rows.
  std::string peridigm = "# x y z block volume\n";
  for (int i = 0; i < 10; ++i)
    for (int row = 0; row < 2; ++row)
      peridigm += std::to_string(i) + " " + std::to_string(row) + " 0 " + std::to_string(row + 1) + " 1\n";
  write("two.txt", peridigm);
  const Result all = run("search two.txt --horizon 1.5 --json");
  EXPECT_OUTPUT(all, "\"neighbors\":92");  // entries: 2 x 18 along the rows, 20 across, 36 diagonal
  const Result split = run("search two.txt --horizon 1.5 --block-pairs 1-1,2-2 --json --vtk two.vtu");
  ASSERT_EQ(split.status, 0) << split.output;
  EXPECT_OUTPUT(split, "\"neighbors\":36");
  EXPECT_OUTPUT(split, "\"block_pairs\":2");
  EXPECT_OUTPUT(split, "\"bonds_cut\":56");
  std::ifstream vtu(dir_ / "two.vtu");
  const std::string xml((std::istreambuf_iterator<char>(vtu)), {});
  EXPECT_NE(xml.find("Name=\"block\""), std::string::npos);
  // --blocks overrides the file's column: every point in block 3.
  write("three.txt", std::string(20 * 2, ' ').replace(0, 40, "3\n3\n3\n3\n3\n3\n3\n3\n3\n3\n3\n3\n3\n3\n3\n3\n3\n3\n3\n3\n"));
  EXPECT_OUTPUT(run("search two.txt --horizon 1.5 --blocks three.txt --block-pairs 3-3 --json"), "\"neighbors\":92");
  expect_refused("search two.txt --horizon 1.5 --block-pairs 1-3", "block pair 1-3: no point is in block 3 (blocks: 1, 2)");
  expect_refused("search two.txt --horizon 1.5 --block-pairs 1-x", "'1-x' is not a pair of block ids");
  expect_refused("search lattice:4 --horizon 3 --block-pairs 1-1", "--block-pairs needs a block per point");
  expect_refused("search lattice:4 --horizon 3 --blocks three.txt", "20 block ids for 64 points");
}

TEST_F(CliTest, RadiiGiveEachPointItsOwnHorizon) {
  // Ten points one apart on a line: point 0 reaches 2.5, the others 0.5 (nobody).
  std::string line, radii = "2.5\n";
  for (int i = 0; i < 10; ++i) line += std::to_string(i) + " 0 0\n";
  for (int i = 1; i < 10; ++i) radii += "0.5\n";
  write("line.txt", line);
  write("radii.txt", radii);
  EXPECT_OUTPUT(run("search line.txt --radii radii.txt --json"), "\"neighbors\":2");  // gather: row 0 = 1, 2
  EXPECT_OUTPUT(run("search line.txt --radii radii.txt --radius-rule scatter --json"), "\"neighbors\":2");
  EXPECT_OUTPUT(run("search line.txt --radii radii.txt --radius-rule max --json"), "\"neighbors\":4");
  EXPECT_OUTPUT(run("search line.txt --radii radii.txt --radius-rule max --half --json"), "\"neighbors\":2");
  EXPECT_OUTPUT(run("search line.txt --radii radii.txt --radius-rule min --json"), "\"neighbors\":0");
  const Result vtk = run("search line.txt --radii radii.txt --vtk line.vtu --quiet");
  ASSERT_EQ(vtk.status, 0) << vtk.output;
  std::ifstream vtu(dir_ / "line.vtu");
  const std::string xml((std::istreambuf_iterator<char>(vtu)), {});
  EXPECT_NE(xml.find("Name=\"radius\""), std::string::npos);
  write("bad.txt", "2.5\n-1\n0.5\n0.5\n0.5\n0.5\n0.5\n0.5\n0.5\n0.5\n");
  expect_refused("search line.txt --radii bad.txt", "radii: point 1 has radius -1.000000 (each must be finite and > 0)");
  write("short.txt", "1\n1\n");
  expect_refused("search line.txt --radii short.txt", "short.txt: 2 radii for 10 points");
  write("word.txt", "1\nwide\n");
  expect_refused("search line.txt --radii word.txt", "word.txt:2: expected one radius (a number)");
  expect_refused("search line.txt --radii radii.txt --half", "a half list needs a symmetric rule (max or min)");
  expect_refused("search line.txt", "--horizon D or --radii FILE is required");
  // With --queries, a radius per query (the gather rule): (0.2, 0) reaches 0 and 1, (5, 0) only
  // point 5, at distance 0 (a query is nobody's "self").
  write("queries.txt", "0.2 0 0\n5 0 0\n");
  write("query_radii.txt", "1.5\n0.5\n");
  EXPECT_OUTPUT(run("search line.txt --queries queries.txt --radii query_radii.txt --json"), "\"neighbors\":3");
  expect_refused("search line.txt --queries queries.txt --radii radii.txt", "radii.txt: 10 radii for 2 queries");
  expect_refused("search line.txt --queries queries.txt --radii query_radii.txt --radius-rule max",
                 "--radii with --queries: only --radius-rule gather");
}

TEST_F(CliTest, MaxMemoryStreamsTheListToItsFilesOrRefusesIt) {
  // A list larger than the memory allowed, with nowhere to stream it to (no --out, CSV, VTK):
  // refused with its size and the ways out.
  const std::string too_large = "needs 11.7 MB (2929168 entries) but 102400 bytes are allowed";
  expect_refused("search lattice:30 --horizon 1.005 --max-memory 100K", too_large);
  expect_refused("search lattice:30 --horizon 1.005 --max-memory 100K --out list --format csv", too_large);
  expect_refused("search lattice:30 --horizon 1.005 --max-memory 100K --out list --vtk list.vtu", too_large);
  EXPECT_FALSE(exists("list.csv"));
  EXPECT_FALSE(exists("list.offsets.npy"));
  // With --out (npy) it is written in batches that fit: the same files as without the limit.
  ASSERT_EQ(run("search lattice:30 --horizon 1.005 --out whole --quiet").status, 0);
  const Result parts = run("search lattice:30 --horizon 1.005 --max-memory 100K --out parts --json");
  ASSERT_EQ(parts.status, 0) << parts.output;
  EXPECT_OUTPUT(parts, "\"written_in_batches\":true");
  EXPECT_OUTPUT(parts, "\"neighbors\":2929168");
  for (const char* file : {".offsets.npy", ".indices.npy"}) {
    std::ifstream a(dir_ / ("whole" + std::string(file)), std::ios::binary), b(dir_ / ("parts" + std::string(file)), std::ios::binary);
    EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(a), {}, std::istreambuf_iterator<char>(b), {})) << file;
  }
  EXPECT_EQ(run("search lattice:30 --horizon 1.005 --max-memory 1G --quiet").status, 0);
  expect_refused("search lattice:30 --horizon 1.005 --max-memory lots", "expected a size");
}

TEST_F(CliTest, GpuMaxMemoryIsASize) {
  // The GPU's limit (SearchOptions::gpu_max_memory; Cuda.FillsWithoutHitBitsWithinAGpuMemoryLimit
  // tests what it does): the same list as without it, and a clear refusal of a non-size.
  ASSERT_EQ(run("search lattice:30 --horizon 1.005 --out whole --quiet").status, 0);
  ASSERT_EQ(run("search lattice:30 --horizon 1.005 --gpu-max-memory 60M --out limited --quiet").status, 0);
  for (const char* file : {".offsets.npy", ".indices.npy"}) {
    std::ifstream a(dir_ / ("whole" + std::string(file)), std::ios::binary), b(dir_ / ("limited" + std::string(file)), std::ios::binary);
    EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(a), {}, std::istreambuf_iterator<char>(b), {})) << file;
  }
  expect_refused("search lattice:30 --horizon 1.005 --gpu-max-memory -2G", "--gpu-max-memory -2G: expected a size");
}


TEST_F(CliTest, StructureFilesGiveTheCellAndGeometry) {
  // One atom in a simple cubic cell of side 1, horizon 1.5: the 6 images at 1 and the 12 at sqrt(2).
  write("sc.extxyz", "1\nLattice=\"1 0 0 0 1 0 0 0 1\" Properties=species:S:1:pos:R:3 pbc=\"T T T\"\nH 0.2 0.3 0.4\n");
  const Result sc = run("search sc.extxyz --horizon 1.5 --outputs d,D,S --out sc --json");
  ASSERT_EQ(sc.status, 0) << sc.output;
  EXPECT_OUTPUT(sc, "\"neighbors\":18");
  EXPECT_OUTPUT(sc, "sc.shifts.npy");
  EXPECT_TRUE(exists("sc.distances.npy") && exists("sc.vectors.npy"));
  EXPECT_OUTPUT(run("search sc.extxyz --horizon 1.5 --pbc 1,1,0 --json"), "\"neighbors\":8");  // a slab: 4 + 4
  EXPECT_OUTPUT(run("search sc.extxyz --horizon 1.5 --self-interaction --half --json"), "\"neighbors\":10");
  // A LAMMPS data file with a tilted box: 2 atoms, the same count as the equivalent --cell.
  write("data.tilted", "two atoms\n\n2 atoms\n1 atom types\n0 2 xlo xhi\n0 2 ylo yhi\n0 3 zlo zhi\n0.5 0 0 xy xz yz\n\n"
                       "Atoms # atomic\n\n2 1 1.0 1.0 1.0\n1 1 0.1 0.2 0.3\n");
  write("two.csv", "0.1 0.2 0.3\n1.0 1.0 1.0\n");
  const Result data = run("search data.tilted --horizon 2.2 --json");
  ASSERT_EQ(data.status, 0) << data.output;
  const Result same = run("search two.csv --horizon 2.2 --cell \"2 0 0 0.5 2 0 0 0 3\" --json");
  const auto count = [](const std::string& json) { return json.substr(json.find("\"neighbors\"")).substr(0, 20); };
  EXPECT_EQ(count(data.output), count(same.output));
}

TEST_F(CliTest, BadStructuresAndCellsAreRefusedWithTheirLineAndKey) {
  write("short.extxyz", "1\nLattice=\"1 0 0 0 1 0 0 0\"\nH 0 0 0\n");
  expect_refused("search short.extxyz --horizon 1", "short.extxyz:2: key Lattice: expected 9 numbers");
  write("few.extxyz", "3\nLattice=\"1 0 0 0 1 0 0 0 1\"\nH 0 0 0\nH 0 0 0.5\n");
  expect_refused("search few.extxyz --horizon 1", "declares 3 atoms but 2 atom lines follow");
  write("cols.extxyz", "1\nProperties=species:S:1:pos:R:3:charge:R:1\nH 0 0 0\n");
  expect_refused("search cols.extxyz --horizon 1", "cols.extxyz:3: expected 5 columns");
  write("flat.extxyz", "1\nLattice=\"1 0 0 0 1 0 0 0 0\" pbc=\"T T T\"\nH 0 0 0\n");
  expect_refused("search flat.extxyz --horizon 1", "vector c has zero length but its axis is periodic");
  write("data.noatoms", "x\n\n0 2 xlo xhi\n0 2 ylo yhi\n0 2 zlo zhi\n\nAtoms\n\n");
  expect_refused("search data.noatoms --horizon 1", "no 'N atoms' line");
  write("data.missing", "x\n\n2 atoms\n0 2 xlo xhi\n0 2 ylo yhi\n0 2 zlo zhi\n\nAtoms # atomic\n\n1 1 0 0 0\n");
  expect_refused("search data.missing --horizon 1", "declares 2 atoms but the Atoms section has 1");
  write("p.csv", "0 0 0\n0.5 0.5 0.5\n");
  expect_refused("search p.csv --horizon 1 --cell \"0 1 0 1 0 0 0 0 1\"", "left-handed");
  expect_refused("search p.csv --horizon 1 --cell \"1 0 0 0 1 0 0 0\"", "--cell: expected 9 numbers");
  expect_refused("search p.csv --horizon 1 --pbc 1,0,1", "--pbc needs --cell");
  expect_refused("search p.csv --horizon 1 --outputs d,x", "'x' is not one of S");
  expect_refused("search p.csv --horizon 1 --outputs d --format csv --out list", "written as .npy files, not csv");
}

}  // namespace
