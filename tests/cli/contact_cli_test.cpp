// `aquatoria regional` with [nesting] parent: the Gulf of Mexico grid as the parent, a smaller
// child grid inside it writes <child>_contact.nc with the ROMS nesting.cdl variables; a child
// reaching outside its parent stops with an error naming its config.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "support/run_command.hpp"

namespace fs = std::filesystem;
using aq::test::run_aquatoria;
using ::testing::HasSubstr;

namespace {

std::string ncdump_h(const fs::path& f) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(("ncdump -h " + f.string() + " 2>&1").c_str(), "r"), pclose);
  char buf[4096];
  while (p && fgets(buf, sizeof buf, p.get()) != nullptr) out += buf;
  return out;
}

void write_child(const fs::path& file, const fs::path& parent_grd, double w, double e) {
  const double m = 0.5 * (w + e);  // side midpoints as in gulf_of_mexico.toml
  std::ofstream(file) << "[regional]\nname = \"gulf_child\"\nproj = \"ME\"\nrlat = 25.0\nrlon = -89.0\n"
                         "uscale = 0.001\npoints = \"lonlat\"\n"
                      << "control_points = [[" << w << ", 22.0], [" << m << ", 22.0], [" << e << ", 22.0], [" << e
                      << ", 25.0], [" << e << ", 28.0], [" << m << ", 28.0], [" << w << ", 28.0], [" << w
                      << ", 25.0]]\ncorners = [1, 3, 5, 7]\nny = 20\nstop_after = \"grid\"\n\n"
                      << "[input]\npath = \"/usr/share/ferret-vis/data/etopo5.cdf\"\n\n[roms]\nenabled = false\n\n"
                      << "[nesting]\nparent = \"" << parent_grd.string() << "\"\n";
}

}  // namespace

TEST(ContactCli, ChildInsideGulfOfMexicoWritesContactPoints) {
  const fs::path dir = fs::temp_directory_path() / ("aq_contact_cli_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto r = run_aquatoria("regional -q -c " + std::string(AQ_SOURCE_DIR) + "/configs/gulf_of_mexico.toml -o " +
                               (dir / "parent").string() + " --no-coastline");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path grd = dir / "parent" / "gulf_of_mexico_grd.nc";
  ASSERT_TRUE(fs::exists(grd));

  write_child(dir / "child.toml", grd, -93.0, -85.0);
  const auto c = run_aquatoria("regional -c " + (dir / "child.toml").string() + " -o " + (dir / "child").string() +
                               " --no-coastline");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_THAT(c.err, HasSubstr("contact: done"));
  const fs::path nc = dir / "child" / "gulf_child_contact.nc";
  ASSERT_TRUE(fs::exists(nc));
  const std::string h = ncdump_h(nc);
  for (const char* v : {"int spherical",
                        "Lm(Ngrids)",
                        "refine_factor(Ngrids)",
                        "donor_grid(Ncontact)",
                        "receiver_grid(Ncontact)",
                        "NstrR(Ncontact)",
                        "NendV(Ncontact)",
                        "contact_region(datum)",
                        "on_boundary(datum)",
                        "Idg(datum)",
                        "Jdg(datum)",
                        "Irg(datum)",
                        "Jrg(datum)",
                        "Xrg(datum)",
                        "Yrg(datum)",
                        "Lweight(datum, nLweights)",
                        "Qweight(datum, nQweights)",
                        "angle(datum)",
                        "mask(datum)",
                        "h(datum)",
                        "f(datum)",
                        "pm(datum)",
                        "pn(datum)",
                        "dndx(datum)",
                        "dmde(datum)",
                        "nLweights = 4",
                        "nQweights = 9"})
    EXPECT_THAT(h, HasSubstr(v));

  // Reaching east of the parent's -80° edge: an error naming the child config, no contact file.
  write_child(dir / "outside.toml", grd, -90.0, -78.0);
  const auto o = run_aquatoria("regional -q -c " + (dir / "outside.toml").string() + " -o " +
                               (dir / "outside").string() + " --no-coastline");
  EXPECT_NE(o.exit_code, 0);
  EXPECT_THAT(o.err, HasSubstr("outside.toml"));
  EXPECT_THAT(o.err, HasSubstr("outside the parent"));
  EXPECT_FALSE(fs::exists(dir / "outside" / "gulf_child_contact.nc"));
  fs::remove_all(dir);
}
