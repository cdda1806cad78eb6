// `campaign gather`: every job's result merged into campaign.csv and a self-contained report.html (cli/campaign.h).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli/campaign.h"
#include "util/output_file.h"

namespace shadetwin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string readFile(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string html(const std::string& s) {
  std::string r;
  for (char ch : s) switch (ch) {
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '&': r += "&amp;"; break;
      case '"': r += "&quot;"; break;
      case '\'': r += "&#39;"; break;
      default: r += ch;
    }
  return r;
}

std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  for (size_t i = 0; i < in.size(); i += 3) {
    const uint32_t n = uint32_t(uint8_t(in[i])) << 16 | (i + 1 < in.size() ? uint32_t(uint8_t(in[i + 1])) << 8 : 0) |
                       (i + 2 < in.size() ? uint32_t(uint8_t(in[i + 2])) : 0);
    out += k[n >> 18 & 63];
    out += k[n >> 12 & 63];
    out += i + 1 < in.size() ? k[n >> 6 & 63] : '=';
    out += i + 2 < in.size() ? k[n & 63] : '=';
  }
  return out;
}

std::string pngImg(const fs::path& p, const std::string& alt, const char* cls = "") {
  return "<img class=\"" + std::string(cls) + "\" alt=\"" + html(alt) + "\" src=\"data:image/png;base64," + base64(readFile(p)) + "\">";
}

// The last `lines` lines of a text file.
std::string tail(const fs::path& p, size_t lines) {
  const std::string t = readFile(p);
  size_t pos = t.size(), n = 0;
  while (pos > 0 && n <= lines)
    if (t[--pos] == '\n') ++n;
  return n > lines ? t.substr(pos + 1) : t;
}

// A CSV file as an HTML table (at most maxRows rows).
std::string csvTable(const fs::path& p, size_t maxRows) {
  std::istringstream in(readFile(p));
  std::string line, out = "<table class=\"data\">";
  size_t row = 0;
  while (std::getline(in, line) && row <= maxRows) {
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (char ch : line) {
      if (ch == '"') quoted = !quoted;
      else if (ch == ',' && !quoted) cells.push_back(cell), cell.clear();
      else cell += ch;
    }
    cells.push_back(cell);
    out += "<tr>";
    for (const auto& c : cells) out += (row == 0 ? "<th>" : "<td>") + html(c) + (row == 0 ? "</th>" : "</td>");
    out += "</tr>";
    ++row;
  }
  if (row > maxRows) out += "<tr><td colspan=\"99\">(more rows in " + html(p.filename().string()) + ")</td></tr>";
  return out + "</table>";
}

struct Row {
  const CampaignJob* job;
  json result;  // {} when missing
  std::string status;
};

std::string str(const json& j, const char* k) {
  if (!j.contains(k) || j[k].is_null()) return "";
  if (j[k].is_string()) return j[k].get<std::string>();
  return j[k].dump();
}

}  // namespace

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string r = "\"";
  for (char ch : s) r += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return r + "\"";
}

int gatherCampaign(const CampaignOptions& opts, const Campaign& c, std::ostream& log) {
  const fs::path out = fs::absolute(campaignOutDir(opts, c));
  if (!fs::is_directory(out / "jobs"))
    throw std::runtime_error(out.string() + ": no results (run the campaign first: shadetwin campaign run " + c.file + ")");
  std::vector<Row> rows;
  std::map<std::string, size_t> counts;
  for (const CampaignJob& job : c.jobs) {
    Row r{&job, json::object(), "missing"};
    const fs::path p = out / "jobs" / job.id / "result.json";
    if (fs::exists(p)) {
      try {
        r.result = json::parse(readFile(p));
        r.status = r.result.value("status", "missing");
      } catch (const json::exception& e) {
        r.status = "missing";
        log << "campaign gather: " << p.string() << ": not valid JSON (" << e.what() << "); counted as missing\n";
      }
    }
    ++counts[r.status];
    rows.push_back(std::move(r));
  }
  // campaign.csv: one row per job; the last two columns (attempts, seconds) are the only ones that depend on the run.
  {
    OutputFile f((out / "campaign.csv").string());
    std::ostream& s = f.stream();
    s << "id,kind,suite,scene,technique,samples,size,device,seed,status,exit_code,identical,total,first_difference,"
         "skip_reason,attempts,seconds\n";
    for (const Row& r : rows) {
      const CampaignJob& j = *r.job;
      const std::string size = j.width ? std::to_string(j.width) + "x" + std::to_string(j.height) : "";
      for (const std::string& v :
           {j.id, j.kind, j.suite, j.sceneName, j.technique, j.samples ? std::to_string(j.samples) : std::string(), size, j.device,
            j.seed >= 0 ? std::to_string(j.seed) : std::string(), r.status, str(r.result, "exit_code"), str(r.result, "identical"),
            str(r.result, "total"), str(r.result, "first_difference"), j.skipReason})
        s << csvField(v) << ",";
      s << str(r.result, "attempts") << ",";
      if (r.result.contains("seconds")) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.3f", r.result["seconds"].get<double>());
        s << buf;
      }
      s << "\n";
    }
    f.commit();
  }
  // report.html: self-contained (styles, a small script and every picture inline).
  std::set<std::string> deviceSet;
  for (const CampaignJob& j : c.jobs) deviceSet.insert(j.device);
  const std::vector<std::string> devices(deviceSet.begin(), deviceSet.end());
  auto rowKey = [](const CampaignJob& j) { return j.groupId; };
  std::vector<std::string> keys;
  std::map<std::string, std::map<std::string, const Row*>> matrix;
  for (const Row& r : rows) {
    const std::string k = rowKey(*r.job);
    if (!matrix.count(k)) keys.push_back(k);
    matrix[k][r.job->device] = &r;
  }
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>shadetwin campaign " << html(c.name) << "</title>\n"
    << "<style>body{font-family:sans-serif;margin:2em;color:#222;background:#fff}h1{margin-bottom:0}table{border-collapse:collapse;"
       "margin:0.5em 0 1.5em}td,th{border:1px solid #bbb;padding:3px 8px;font-size:13px;text-align:left}th{background:#eee}"
       ".passed{background:#c8f0c8}.differs{background:#ffd27a}.failed,.missing{background:#f4a0a0}.skipped{background:#ddd;"
       "color:#666}.badge{display:inline-block;padding:4px 10px;margin:4px 6px 4px 0;border-radius:4px;font-weight:bold}"
       "pre{background:#f6f6f6;padding:8px;overflow:auto;max-height:24em;font-size:12px}img.heat{max-width:100%;border:1px "
       "solid #999}img.thumb{max-width:320px;margin:4px;border:1px solid #999}img.plot{max-width:48%;margin:4px}"
       "tr.hidden{display:none}.gallery figure{display:inline-block;margin:4px}</style></head><body>\n";
  h << "<h1>Campaign " << html(c.name) << "</h1>\n<p>" << html(c.description) << "</p>\n<p>" << c.jobs.size()
    << " jobs from <code>" << html(c.file) << "</code>, results in <code>" << html(out.string()) << "</code>.</p>\n<p id=\"counts\">";
  for (const char* st : {"passed", "differs", "failed", "missing", "skipped"})
    if (counts[st]) h << "<span class=\"badge " << st << "\">" << counts[st] << " " << st << "</span>";
  h << "</p>\n<h2>Pass/fail matrix</h2>\n<label><input type=\"checkbox\" id=\"onlyProblems\"> only rows where a job differs, "
       "failed or is missing</label>\n<table id=\"matrix\"><tr><th>job</th>";
  for (const auto& d : devices) h << "<th>" << (d.empty() ? "(no device)" : html(d)) << "</th>";
  h << "</tr>\n";
  for (const auto& k : keys) {
    bool problem = false;
    std::string cells;
    for (const auto& d : devices) {
      const auto it = matrix[k].find(d);
      if (it == matrix[k].end()) {
        cells += "<td></td>";
        continue;
      }
      const Row& r = *it->second;
      problem |= r.status == "differs" || r.status == "failed" || r.status == "missing";
      std::string text = r.status;
      if (r.result.contains("identical")) text += " " + str(r.result, "identical") + "/" + str(r.result, "total");
      const std::string title = !r.job->skipReason.empty() ? r.job->skipReason : str(r.result, "first_difference");
      cells += "<td class=\"" + r.status + "\" title=\"" + html(title) + "\"><a href=\"#" + html(r.job->id) + "\">" + html(text) + "</a></td>";
    }
    h << "<tr data-problem=\"" << (problem ? 1 : 0) << "\"><td>" << html(k) << "</td>" << cells << "</tr>\n";
  }
  h << "</table>\n";
  auto section = [&](const std::string& title, auto pred, auto body) {
    bool any = false;
    for (const Row& r : rows)
      if (pred(r)) {
        if (!any) h << "<h2>" << title << "</h2>\n";
        any = true;
        h << "<h3 id=\"" << html(r.job->id) << "\">" << html(r.job->id) << " <span class=\"badge " << r.status << "\">" << r.status
          << "</span></h3>\n";
        body(r, out / "jobs" / r.job->id);
      }
  };
  section("Differences", [](const Row& r) { return r.status == "differs"; }, [&](const Row& r, const fs::path& dir) {
    if (fs::exists(dir / "report.json")) {
      try {
        const json rep = json::parse(readFile(dir / "report.json"));
        h << "<table><tr><th>case</th><th>identical</th><th>ULP 1</th><th>2-3</th><th>4-15</th><th>16-255</th><th>&ge;256</th>"
             "<th>first difference</th></tr>\n";
        for (const json& cs : rep.at("cases")) {
          const bool same = cs.at("identical") == cs.at("total");
          h << "<tr class=\"" << (same ? "passed" : "differs") << "\"><td>" << html(cs.at("name").get<std::string>()) << "</td><td>"
            << cs.at("identical").dump() << "/" << cs.at("total").dump() << "</td>";
          for (const json& n : cs.at("ulp_histogram")) h << "<td>" << n.dump() << "</td>";
          std::string first;
          if (const json& d = cs.at("first_difference"); !d.is_null()) {
            char buf[96];
            std::snprintf(buf, sizeof buf, "emulator 0x%08llx, device 0x%08llx", (unsigned long long)d.at("emulator_bits").get<uint64_t>(),
                          (unsigned long long)d.at("device_bits").get<uint64_t>());
            first = (d.contains("x") ? "pixel (" + d["x"].dump() + ", " + d["y"].dump() + ")" : "element " + d.at("index").dump()) + ": " + buf;
          }
          h << "<td>" << html(first) << "</td></tr>\n";
        }
        h << "</table>\n";
      } catch (const json::exception& e) {
        h << "<p>report.json unreadable: " << html(e.what()) << "</p>\n";
      }
    }
    if (fs::exists(dir / "heatmap.png")) h << pngImg(dir / "heatmap.png", "ULP heat map of " + r.job->id, "heat") << "\n";
    (void)r;
  });
  section("Failures", [](const Row& r) { return r.status == "failed" || r.status == "missing"; }, [&](const Row& r, const fs::path& dir) {
    if (r.status == "missing") {
      h << "<p>No result: the job has not run (or its result file is damaged).</p>\n";
      return;
    }
    h << "<p>exit status " << html(str(r.result, "exit_code").empty() ? "none" : str(r.result, "exit_code"))
      << (r.result.value("timed_out", false) ? ", timed out" : "") << ", " << str(r.result, "attempts") << " attempt(s); the log's end:</p>\n";
    if (fs::exists(dir / "stdout.txt")) h << "<pre>" << html(tail(dir / "stdout.txt", 40)) << "</pre>\n";
  });
  section("Sweeps", [](const Row& r) { return r.job->kind == "sweep" && r.status == "passed"; }, [&](const Row&, const fs::path& dir) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir / "sweep", ec)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files)
      if (f.extension() == ".csv") h << "<h4>" << html(f.filename().string()) << "</h4>\n" << csvTable(f, 200) << "\n";
    for (const auto& f : files)
      if (f.extension() == ".png") h << pngImg(f, f.filename().string(), "plot") << "\n";
  });
  bool anyRender = false;
  for (const Row& r : rows)
    if (r.job->kind == "render" && r.status == "passed" && fs::exists(out / "jobs" / r.job->id / "render.png")) {
      if (!anyRender) h << "<h2>Renders</h2>\n<div class=\"gallery\">\n";
      anyRender = true;
      h << "<figure id=\"" << html(r.job->id) << "\">" << pngImg(out / "jobs" / r.job->id / "render.png", r.job->id, "thumb")
        << "<figcaption>" << html(r.job->id) << "</figcaption></figure>\n";
    }
  if (anyRender) h << "</div>\n";
  section("Performance model", [](const Row& r) { return r.job->kind == "model" && r.status == "passed"; },
          [&](const Row&, const fs::path& dir) { h << "<pre>" << html(tail(dir / "stdout.txt", 60)) << "</pre>\n"; });
  bool anySkipped = false;
  for (const Row& r : rows)
    if (r.status == "skipped") {
      if (!anySkipped) h << "<h2>Skipped by the plan</h2>\n<table><tr><th>job</th><th>reason</th></tr>\n";
      anySkipped = true;
      h << "<tr id=\"" << html(r.job->id) << "\"><td>" << html(r.job->id) << "</td><td>" << html(r.job->skipReason) << "</td></tr>\n";
    }
  if (anySkipped) h << "</table>\n";
  h << "<script>\n"
       "const box = document.getElementById('onlyProblems');\n"
       "box.addEventListener('change', () => {\n"
       "  for (const row of document.querySelectorAll('#matrix tr[data-problem]'))\n"
       "    row.classList.toggle('hidden', box.checked && row.dataset.problem === '0');\n"
       "});\n"
       "</script>\n</body></html>\n";
  {
    OutputFile f((out / "report.html").string());
    f.stream() << h.str();
    f.commit();
  }
  log << "campaign " << c.name << ": " << counts["passed"] << " passed, " << counts["differs"] << " differ, " << counts["failed"]
      << " failed, " << counts["missing"] << " missing, " << counts["skipped"] << " skipped; wrote " << (out / "campaign.csv").string()
      << " and " << (out / "report.html").string() << "\n";
  return (counts["differs"] || counts["failed"] || counts["missing"]) ? 1 : 0;
}

}  // namespace shadetwin
