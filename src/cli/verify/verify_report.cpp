// verify --junit / --json: a suite's comparison as JUnit XML (what CI systems read: Jenkins, GitLab, GitHub actions'
// test reporters) and as JSON (tests/verify_report.schema.json), one test case per stage and channel group.
#include <filesystem>
#include <bit>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "cli/verify/verify.h"
#include "util/heatmap.h"
#include "util/output_file.h"

namespace shadetwin {
namespace {

std::string xmlEscape(const std::string& s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      case '\'': r += "&apos;"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') r += ' ';  // not allowed in XML 1.0
        else r += c;
    }
  }
  return r;
}

std::string jsonEscape(const std::string& s) {
  std::ostringstream r;
  for (char c : s) {
    if (c == '"' || c == '\\') r << '\\' << c;
    else if (static_cast<unsigned char>(c) < 0x20) r << "\\u" << std::hex << std::setw(4) << std::setfill('0') << int(c) << std::dec;
    else r << c;
  }
  return r.str();
}

// "element i" or, for an image comparison of `width` pixels a row, "pixel (x, y)".
std::string where(const UlpTally& t, uint32_t width) {
  if (t.firstDiff < 0) return "";
  if (!width) return "element " + std::to_string(t.firstDiff);
  return "pixel (" + std::to_string(uint64_t(t.firstDiff) % width) + ", " + std::to_string(uint64_t(t.firstDiff) / width) + ")";
}

std::string failureMessage(const UlpTally& t, uint32_t width) {
  std::ostringstream m;
  m << t.identical << "/" << t.total << " bit-identical; first difference at " << where(t, width);
  if (t.firstDiff >= 0) m << " (emulator " << std::setprecision(9) << t.firstA << ", device " << t.firstB << ")";
  return m.str();
}

// --heatmap: a panel per differing case of an image comparison, its elements laid out `width` a row.
void writeHeatMap(const VerifyOptions& opts, const VerifyReport& r, std::ostream& out) {
  if (!r.width) {
    out << "heat map: not written (verify " << r.suite << " compares no image: its elements are not pixels)\n";
    return;
  }
  std::vector<HeatPanel> panels;
  bool truncated = false;
  for (const UlpTally& t : r.cases) {
    if (t.identical == t.total) continue;
    HeatPanel p{t.name, r.width, uint32_t((t.total + r.width - 1) / r.width), {}};
    p.ulp.assign(size_t(p.width) * p.height, 0);
    for (const auto& [i, u] : t.diffs) p.ulp[i] = u;
    truncated |= t.diffsTruncated;
    panels.push_back(std::move(p));
  }
  if (panels.empty()) {
    out << "heat map: not written (nothing differs)\n";
    return;
  }
  const std::string title = "verify " + r.suite + (r.scene.empty() ? "" : " " + std::filesystem::path(r.scene).filename().string()) +
                            " on " + r.device +
                            ": ULP distance, emulator vs device";
  const std::string warning = writeUlpHeatMap(opts.heatmap, title, panels);
  out << "heat map: " << opts.heatmap << " (" << panels.size() << " differing channels"
      << (truncated ? "; only the first 16M differences of a channel are drawn" : "") << ")\n";
  if (!warning.empty()) out << warning << "\n";
}

}  // namespace

void writeVerifyReports(const VerifyOptions& opts, const VerifyReport& r, std::ostream& out) {
  if (!opts.heatmap.empty()) writeHeatMap(opts, r, out);
  size_t failures = 0;
  for (const UlpTally& t : r.cases) failures += t.identical != t.total;
  const bool validationFailed = r.validationErrors > 0;
  if (!opts.junit.empty()) {
    OutputFile f(opts.junit);
    std::ostream& o = f.stream();
    o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    o << "<testsuites name=\"shadetwin verify\" tests=\"" << r.cases.size() + 1 << "\" failures=\""
      << failures + validationFailed << "\" errors=\"0\">\n";
    o << "  <testsuite name=\"verify " << xmlEscape(r.suite) << "\" tests=\"" << r.cases.size() + 1 << "\" failures=\""
      << failures + validationFailed << "\" errors=\"0\" skipped=\"0\">\n";
    o << "    <properties>\n";
    o << "      <property name=\"device\" value=\"" << xmlEscape(r.device) << "\"/>\n";
    if (!r.scene.empty()) o << "      <property name=\"scene\" value=\"" << xmlEscape(r.scene) << "\"/>\n";
    o << "    </properties>\n";
    for (const UlpTally& t : r.cases) {
      o << "    <testcase classname=\"verify." << xmlEscape(r.suite) << "\" name=\"" << xmlEscape(t.name) << "\"";
      if (t.identical == t.total) {
        o << "/>\n";
        continue;
      }
      o << ">\n      <failure message=\"" << xmlEscape(failureMessage(t, r.width)) << "\" type=\"bits differ\">"
        << "differing by ULP: 1: " << t.hist[0] << ", 2-3: " << t.hist[1] << ", 4-15: " << t.hist[2] << ", 16-255: " << t.hist[3]
        << ", >=256: " << t.hist[4] << "</failure>\n    </testcase>\n";
    }
    o << "    <testcase classname=\"verify." << xmlEscape(r.suite) << "\" name=\"validation layers\"";
    if (!validationFailed) o << "/>\n";
    else
      o << ">\n      <failure message=\"" << r.validationErrors << " validation errors\" type=\"validation\">"
        << xmlEscape(r.lastValidationMessage) << "</failure>\n    </testcase>\n";
    o << "  </testsuite>\n</testsuites>\n";
    f.commit();
  }
  if (!opts.json.empty()) {
    OutputFile f(opts.json);
    std::ostream& o = f.stream();
    size_t I = 0, T = 0;
    for (const UlpTally& t : r.cases) I += t.identical, T += t.total;
    o << "{\n  \"suite\": \"" << jsonEscape(r.suite) << "\",\n  \"device\": \"" << jsonEscape(r.device) << "\",\n";
    o << "  \"scene\": " << (r.scene.empty() ? "null" : "\"" + jsonEscape(r.scene) + "\"") << ",\n";
    o << "  \"width\": " << r.width << ",\n  \"identical\": " << I << ",\n  \"total\": " << T << ",\n";
    o << "  \"validation_errors\": " << r.validationErrors << ",\n";
    o << "  \"passed\": " << (I == T && !validationFailed ? "true" : "false") << ",\n  \"cases\": [";
    for (size_t k = 0; k < r.cases.size(); ++k) {
      const UlpTally& t = r.cases[k];
      o << (k ? ",\n" : "\n") << "    {\"name\": \"" << jsonEscape(t.name) << "\", \"identical\": " << t.identical
        << ", \"total\": " << t.total << ", \"ulp_histogram\": [" << t.hist[0] << ", " << t.hist[1] << ", " << t.hist[2]
        << ", " << t.hist[3] << ", " << t.hist[4] << "], \"first_difference\": ";
      if (t.firstDiff < 0) {
        o << "null}";
      } else {
        o << "{\"index\": " << t.firstDiff;
        if (r.width) o << ", \"x\": " << uint64_t(t.firstDiff) % r.width << ", \"y\": " << uint64_t(t.firstDiff) / r.width;
        o << ", \"emulator_bits\": " << std::bit_cast<uint32_t>(t.firstA) << ", \"device_bits\": " << std::bit_cast<uint32_t>(t.firstB)
          << "}}";
      }
    }
    o << "\n  ]\n}\n";
    f.commit();
  }
}

}  // namespace shadetwin
