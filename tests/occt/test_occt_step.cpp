// The STEP file of `--output FILE.stp` read back with OpenCASCADE (a test
// dependency only): the curve OCCT builds is compared with `uniparam sample`
// on the same map at 100 parameters, and OCCT's length of it with uniparam's
// certified arc length mu (parametric speed).
#include <BRep_Tool.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <Geom_BSplineCurve.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Pnt.hxx>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

std::string bin() {
  const char* b = std::getenv("UNIPARAM_BIN");
  return b ? b : "uniparam";
}

// stdout of a shell command; the exit status in *status.
std::string run(const std::string& cmd, int* status) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  std::size_t k;
  while ((k = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, k);
  *status = pclose(p);
  return out;
}

std::string temp_step() {
  char name[] = "/tmp/uniparam_occt_XXXXXX";
  const int fd = mkstemp(name);
  close(fd);
  unlink(name);
  return std::string(name) + ".stp";
}

// The first (and only) B-spline curve of a STEP file, with its parameter range.
Handle(Geom_BSplineCurve) read_curve(const std::string& path, double* first, double* last) {
  STEPControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) return nullptr;
  reader.TransferRoots();
  const TopoDS_Shape shape = reader.OneShape();
  for (TopExp_Explorer e(shape, TopAbs_EDGE); e.More(); e.Next()) {
    Handle(Geom_Curve) c = BRep_Tool::Curve(TopoDS::Edge(e.Current()), *first, *last);
    Handle(Geom_BSplineCurve) b = Handle(Geom_BSplineCurve)::DownCast(c);
    if (!b.IsNull()) return b;
  }
  return nullptr;
}

struct Row {
  double s, x, y;
};

// The CSV rows (s, t, x, y, speed) of `uniparam sample`.
std::vector<Row> sample_rows(const std::string& text) {
  std::vector<Row> rows;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::istringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) v.push_back(cell.empty() ? NAN : std::strtod(cell.c_str(), nullptr));
    if (v.size() >= 4) rows.push_back({v[0], v[2], v[3]});
  }
  return rows;
}

// The "mid" and "rad" of the JSON key `key` (first occurrence).
void json_ball(const std::string& j, const std::string& key, double* mid, double* rad) {
  const std::size_t k = j.find("\"" + key + "\"");
  ASSERT_NE(k, std::string::npos) << key;
  const std::size_t m = j.find("\"mid\": \"", k);
  const std::size_t r = j.find("\"rad\": \"", k);
  *mid = std::strtod(j.c_str() + m + 8, nullptr);
  *rad = std::strtod(j.c_str() + r + 8, nullptr);
}

// `map` selects the same map for reparam (its options) and sample (--method ...).
// `curve` is the curve's arguments, shell-quoted ("'(t, t^2)'", "--svg 'M ...'").
void check(const std::string& curve, const std::string& reparam_map, const std::string& sample_map) {
  const std::string path = temp_step();
  int st = 0;
  const std::string common = " " + curve + " --speed parametric --digits 15 ";
  const std::string report = run(bin() + " reparam" + common + reparam_map + " --json --output " + path, &st);
  ASSERT_EQ(st, 0) << report;
  double first = 0, last = 0;
  Handle(Geom_BSplineCurve) b = read_curve(path, &first, &last);
  std::remove(path.c_str());
  ASSERT_FALSE(b.IsNull()) << "OCCT read no B-spline curve from the STEP file";
  EXPECT_TRUE(b->IsRational());
  EXPECT_DOUBLE_EQ(first, 0.0);
  EXPECT_DOUBLE_EQ(last, 1.0);

  const std::string csv = run(bin() + " sample" + common + sample_map + " --points 100", &st);
  ASSERT_EQ(st, 0) << csv;
  const std::vector<Row> rows = sample_rows(csv);
  ASSERT_EQ(rows.size(), 100u);
  for (const Row& r : rows) {
    const gp_Pnt p = b->Value(r.s);
    // STEP carries doubles: a relative error of a few ulps of the data
    const double scale = 1 + std::fabs(r.x) + std::fabs(r.y);
    EXPECT_NEAR(p.X(), r.x, 1e-12 * scale) << "s = " << r.s;
    EXPECT_NEAR(p.Y(), r.y, 1e-12 * scale) << "s = " << r.s;
    EXPECT_NEAR(p.Z(), 0.0, 1e-15);
  }

  double mu = 0, rad = 0;
  json_ball(report, "mu", &mu, &rad);
  const double tol = 1e-10;
  GeomAdaptor_Curve ad(b);
  const double L = GCPnts_AbscissaPoint::Length(ad, first, last, tol);
  EXPECT_LE(std::fabs(L - mu), rad + tol * (1 + mu)) << "OCCT length " << L << ", uniparam mu " << mu;
}

TEST(OcctStep, C0PiecesMatchSampleAndLength) {
  check("'(t, t^3/(1+t^2))'", "--pieces 3", "--method c0 --pieces 3");
}

TEST(OcctStep, C1TargetMatchesSampleAndLength) {
  check("'((1-t^2)/(1+t^2), 2*t/(1+t^2))'", "--target 0.999", "--method c1 --target 0.999");
}

TEST(OcctStep, SubdividedPiecesMatchSampleAndLength) {
  // W = t^2 - t + 3/10 > 0 has a negative Bernstein coefficient: pieces subdivided
  check("'(t/(t^2-t+3/10), 1/(t^2-t+3/10))'", "--pieces 2", "--method c0 --pieces 2");
}

TEST(OcctStep, CompositePathOfMixedDegreesMatchesSampleAndLength) {
  // A line, a quadratic and a cubic: one NURBS of degree 3 (the line and the
  // quadratic raised), pieces shared over the path.
  check("--svg 'M 0 0 L 3 0 Q 4 0 4 1 C 4 2 3 3 2 3'", "--pieces 5", "--method c0 --pieces 5");
  check("--svg 'M 0 0 L 3 0 Q 4 0 4 1 C 4 2 3 3 2 3'", "--target 0.999", "--method c1 --target 0.999");
}

}  // namespace
