// SPDX-License-Identifier: GPL-3.0-or-later
// SCHISM floods the shipped storm-surge mesh (README "A storm-surge mesh"): configs/gulf_surge.toml
// is meshed into hgrid.gr3 and SCHISM (2 MPI ranks) runs it for 24 hours with a 2 m M2 on the open
// boundary; SCHISM wets and dries by itself (param.nml h0 = 0.01 m).
//
// The client (../shared/clients/schism/schism.sh) raises every depth shallower than --h0 (>= 0) to
// it, which would flatten the floodplain to the datum. So the client sets the run up (a one-step
// run writes bctides.in for our open segment, param.nml, vgrid.in, drag.gr3, adv.gr3 and the
// partition), and SCHISM then runs 24 hours in a second folder on our hgrid.gr3 as written
// (negative depths kept), with the client's param.nml for a day (rnday 1, dt 300 s, hourly
// output: the values `schism.sh run ... 24` writes). Asserted from SCHISM's own files: normal end
// after 288 steps, no NaN in the hourly elevations, the wet elevations of the order of the
// forcing, and floodplain nodes (negative depth in our file) wet at some hourly record
// (wetdry_node = 0). Skipped when ../shared/clients/schism is absent.
#include <gtest/gtest.h>
#include <netcdf.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/client_summary.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace schism_schism_surge_test {

namespace {

namespace fs = std::filesystem;

// The client's param.nml with the values of a 24-hour run at its default Δt = 300 s (hourly records
// in one stack), as `schism.sh run GR3 24` writes them.
std::string day_run(std::string nml) {
  for (const auto& [key, value] :
       {std::pair{"rnday", "1"}, std::pair{"dt", "300"}, std::pair{"nspool", "12"}, std::pair{"ihfskip", "288"}}) {
    const std::regex re(std::string("\\n\\s*") + key + "\\s*=\\s*([^\\s!]+)");
    std::smatch m;
    if (!std::regex_search(nml, m, re)) {
      ADD_FAILURE() << key << " not in param.nml";
      continue;
    }
    const auto at = static_cast<std::size_t>(m.position(1));
    nml = nml.substr(0, at) + value + nml.substr(at + static_cast<std::size_t>(m.length(1)));
  }
  return nml;
}

// Global node ids (1-based) of a rank's local nodes (outputs/local_to_global_RANK: a header line,
// a title line, the local element count and its lines, the local node count and its lines).
std::vector<long> local_nodes(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  long ne = 0, np = 0, a = 0, b = 0;
  in >> ne;
  for (long k = 0; k < ne; ++k) in >> a >> b;
  in >> np;
  std::vector<long> g(static_cast<std::size_t>(std::max<long>(np, 0)));
  for (long k = 0; k < np; ++k) in >> a >> g[static_cast<std::size_t>(k)];
  if (!in) g.clear();
  return g;
}

struct Records {
  std::size_t times = 0, nodes = 0;
  std::vector<float> elev, wetdry;  // [time][node]
  std::string error;
};

Records read_records(const fs::path& p) {
  Records r;
  int nc = -1, d = -1, v = -1;
  if (nc_open(p.c_str(), NC_NOWRITE, &nc) != NC_NOERR) {
    r.error = "cannot open " + p.string();
    return r;
  }
  if (nc_inq_dimid(nc, "time", &d) != NC_NOERR || nc_inq_dimlen(nc, d, &r.times) != NC_NOERR ||
      nc_inq_dimid(nc, "nSCHISM_hgrid_node", &d) != NC_NOERR || nc_inq_dimlen(nc, d, &r.nodes) != NC_NOERR) {
    r.error = p.string() + ": no time or node dimension";
  } else {
    r.elev.resize(r.times * r.nodes);
    r.wetdry.resize(r.times * r.nodes);
    if (nc_inq_varid(nc, "elev", &v) != NC_NOERR || nc_get_var_float(nc, v, r.elev.data()) != NC_NOERR ||
        nc_inq_varid(nc, "wetdry_node", &v) != NC_NOERR || nc_get_var_float(nc, v, r.wetdry.data()) != NC_NOERR)
      r.error = p.string() + ": no elev or wetdry_node";
  }
  nc_close(nc);
  return r;
}

TEST(SchismSurge, GulfSurgeFloodplainWetsAndDriesForADay) {
  const fs::path script = aq::test::client_script("schism", "schism.sh");
  if (!fs::exists(script)) GTEST_SKIP() << "SCHISM client test skipped: " << script.string() << " not found";
  const aq::testing::TempDir dir;
  const auto mesh = aq::test::run_command(std::string(AQ_BINARY) + " mesh -q -o " + dir.path().string() + " -c " +
                                          (fs::path(AQ_SOURCE_DIR) / "configs" / "gulf_surge.toml").string() +
                                          " --set 'output.formats=[\"schism\"]'");
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  const fs::path gr3 = dir / "gulf_surge.gr3";
  std::set<long> floodplain;  // 1-based ids of the nodes above the datum
  long ne = 0, np = 0;
  {
    std::ifstream f(gr3);
    std::string line;
    std::getline(f, line);
    f >> ne >> np;
    for (long k = 0; k < np; ++k) {
      long id = 0;
      double x = 0, y = 0, depth = 0;
      f >> id >> x >> y >> depth;
      if (depth < 0.0) floodplain.insert(id);
    }
    ASSERT_TRUE(f) << gr3.string();
  }
  ASSERT_GT(floodplain.size(), 100u) << "the floodplain is in the file";

  // The client's set-up: one step of 300 s on its own (clamped) copy.
  const fs::path setup = dir / "setup", run = dir / "run";
  const auto first = aq::test::run_command("bash " + script.string() + " run " + gr3.string() +
                                           " 0.0833333 --open-m2 2.0 --h0 0 --workdir " + setup.string());
  ASSERT_EQ(first.exit_code, 0) << first.err;
  ASSERT_EQ(aq::test::key_values(first.out)["schism_status"], "normal") << first.out << first.err;
  fs::create_directories(run / "outputs");
  for (const char* f : {"bctides.in", "vgrid.in", "drag.gr3", "adv.gr3", "partition.prop"})
    fs::copy_file(setup / f, run / f);
  fs::copy_file(gr3, run / "hgrid.gr3");
  fs::copy_file(gr3, run / "hgrid.ll");
  std::ofstream(run / "param.nml") << day_run(aq::test::slurp(setup / "param.nml"));
  const char* cache = std::getenv("SCHISM_CACHE");
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  const fs::path bin = (cache != nullptr && *cache != '\0') ? fs::path(cache) / "bin" / "pschism"
                       : (xdg != nullptr && *xdg != '\0')
                           ? fs::path(xdg) / "aq-schism" / "bin" / "pschism"
                           : fs::path(home != nullptr ? home : "") / ".cache" / "aq-schism" / "bin" / "pschism";
  ASSERT_TRUE(fs::exists(bin)) << bin.string();
  const auto sim = aq::test::run_command("cd " + run.string() +
                                         " && OMPI_MCA_btl_vader_single_copy_mechanism=none mpirun --oversubscribe "
                                         "--bind-to none -np 2" +
                                         std::string(::geteuid() == 0 ? " --allow-run-as-root " : " ") + bin.string() +
                                         " > screen.log 2>&1");
  const std::string mirror = aq::test::slurp(run / "outputs" / "mirror.out");
  ASSERT_NE(mirror.find("Run completed successfully"), std::string::npos)
      << "SCHISM did not end normally (exit " << sim.exit_code
      << "): " << aq::test::slurp(run / "outputs" / "fatal.error") << aq::test::slurp(run / "screen.log");
  EXPECT_NE(mirror.find("TIME STEP=          288;"), std::string::npos) << "288 steps of 300 s";

  std::set<long> flooded;
  double wet_max = 0.0;
  std::size_t records = 0;
  for (int rank = 0; rank < 2; ++rank) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d", rank);
    const std::vector<long> global = local_nodes(run / "outputs" / (std::string("local_to_global_") + name));
    const Records r = read_records(run / "outputs" / (std::string("schout_") + name + "_1.nc"));
    ASSERT_TRUE(r.error.empty()) << r.error;
    ASSERT_EQ(global.size(), r.nodes) << "rank " << rank;
    records = r.times;
    for (std::size_t t = 0; t < r.times; ++t)
      for (std::size_t k = 0; k < r.nodes; ++k) {
        const float e = r.elev[t * r.nodes + k];
        ASSERT_TRUE(std::isfinite(e)) << "NaN at hour " << t + 1 << ", node " << global[k];
        if (r.wetdry[t * r.nodes + k] != 0.0f) continue;  // dry
        wet_max = std::max(wet_max, static_cast<double>(std::fabs(e)));
        if (floodplain.count(global[k]) != 0) flooded.insert(global[k]);
      }
  }
  std::cout << "SCHISM on gulf_surge.gr3 as written (negative depths kept), 24 h, M2 2 m on the open boundary: "
            << floodplain.size() << " floodplain nodes, " << flooded.size() << " wet at some hourly record; max |η| "
            << wet_max << " m at wet nodes over " << records << " records\n";
  EXPECT_EQ(records, 24u);
  EXPECT_GT(flooded.size(), 5u) << "floodplain nodes that flood";
  EXPECT_LT(flooded.size(), floodplain.size()) << "the higher floodplain stays dry";
  EXPECT_GT(wet_max, 1.0);
  EXPECT_LT(wet_max, 10.0);
}

}  // namespace

}  // namespace schism_schism_surge_test
