#include "cosim/explore/sweep_table.hpp"
#include "cosim/reports/files.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include "refmodel/error.hpp"

namespace voxcast::cosim::sweep {
namespace {

// Shortest text that reads back to the same double (std::to_chars).
std::string number_text(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

const char* kind_name(Column::Kind k) { return k == Column::Kind::Number ? "number" : "text"; }

}  // namespace

std::size_t Table::column(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i].name == name) return i;
  throw Error("sweep table: no column \"" + name + "\"");
}

std::string point_label(const Table& table, const Row& row) {
  std::string label;
  const std::size_t axes = table.meta.at("axes").size();
  for (std::size_t a = 0; a < axes && a < row.cells.size(); ++a) {
    const std::string& key = table.columns[a].name;
    const std::size_t dot = key.rfind('.');
    if (!label.empty()) label += ' ';
    label += (dot == std::string::npos ? key : key.substr(dot + 1)) + "=" + row.cells[a].text;
  }
  return label;
}

std::vector<std::optional<bool>> pareto_front(
    const std::vector<std::vector<std::optional<double>>>& points,
    const std::vector<bool>& maximize) {
  const auto available = [](const std::vector<std::optional<double>>& p) {
    return std::all_of(p.begin(), p.end(), [](const auto& v) { return v.has_value(); });
  };
  // p dominates q: at least as good everywhere, strictly better somewhere.
  const auto dominates = [&](const auto& p, const auto& q) {
    bool strictly = false;
    for (std::size_t k = 0; k < maximize.size(); ++k) {
      const double a = maximize[k] ? *p[k] : -*p[k];
      const double b = maximize[k] ? *q[k] : -*q[k];
      if (a < b) return false;
      if (a > b) strictly = true;
    }
    return strictly;
  };
  std::vector<std::optional<bool>> on(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].size() != maximize.size())
      throw Error("pareto_front: a point has " + std::to_string(points[i].size()) +
                  " objectives, expected " + std::to_string(maximize.size()));
    if (!available(points[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < points.size() && !dominated; ++j)
      dominated = j != i && available(points[j]) && dominates(points[j], points[i]);
    on[i] = !dominated;
  }
  return on;
}

void mark_front(Table& table, const Front& front) {
  const std::size_t status = table.column("status");
  std::size_t col;
  try {
    col = table.column(front.column.name);
  } catch (const Error&) {
    table.columns.push_back(front.column);
    col = table.columns.size() - 1;
    for (Row& r : table.rows) r.cells.resize(table.columns.size());
  }
  std::vector<std::size_t> obj;
  std::vector<bool> maximize;
  for (const Objective& o : front.objectives) {
    obj.push_back(table.column(o.column));
    maximize.push_back(o.maximize);
  }
  std::vector<std::vector<std::optional<double>>> points;
  for (const Row& r : table.rows) {
    std::vector<std::optional<double>> p;
    const bool ok = r.cells[status].kind == Cell::Kind::Text && r.cells[status].text == "ok";
    for (std::size_t c : obj) p.push_back(ok ? r.cells[c].value() : std::nullopt);
    points.push_back(std::move(p));
  }
  const std::vector<std::optional<bool>> on = pareto_front(points, maximize);
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    Cell& cell = table.rows[i].cells[col];
    if (on[i]) {
      cell = Cell::txt(*on[i] ? "yes" : "no");
      continue;
    }
    std::string missing;
    for (std::size_t k = 0; k < obj.size(); ++k)
      if (!points[i][k]) missing += (missing.empty() ? "" : " and ") + front.objectives[k].column;
    const Cell& st = table.rows[i].cells[status];
    cell = Cell::na(st.kind == Cell::Kind::Text && st.text == "ok"
                        ? front.column.name + ": " + missing + " not available"
                        : front.column.name + ": the point did not run");
  }
}

void write_csv(const Table& t, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot write");
  for (const Column& c : t.columns) out << csv_field(c.name) << ",";
  out << "notes\n";
  for (const Row& r : t.rows) {
    std::vector<std::string> notes;
    for (std::size_t c = 0; c < t.columns.size(); ++c) {
      const Cell& cell = r.cells[c];
      if (cell.kind == Cell::Kind::Number) out << number_text(cell.number);
      if (cell.kind == Cell::Kind::Text) out << csv_field(cell.text);
      if (cell.kind == Cell::Kind::NotAvailable &&
          std::find(notes.begin(), notes.end(), cell.text) == notes.end())
        notes.push_back(cell.text);
      out << ",";
    }
    std::string joined;
    for (const std::string& n : notes) joined += (joined.empty() ? "" : "; ") + n;
    out << csv_field(joined) << "\n";
  }
  if (!out) throw Error(path + ": write failed");
}

nlohmann::json to_json(const Table& t) {
  nlohmann::json j;
  j["sweep"] = t.meta;
  j["columns"] = nlohmann::json::array();
  for (const Column& c : t.columns)
    j["columns"].push_back(
        {{"name", c.name}, {"kind", kind_name(c.kind)}, {"unit", c.unit}, {"doc", c.doc}});
  j["rows"] = nlohmann::json::array();
  for (const Row& r : t.rows) {
    nlohmann::json cells = nlohmann::json::object(), na = nlohmann::json::object();
    for (std::size_t c = 0; c < t.columns.size(); ++c) {
      const Cell& cell = r.cells[c];
      const std::string& name = t.columns[c].name;
      if (cell.kind == Cell::Kind::Number)
        cells[name] = std::isinf(cell.number) ? nlohmann::json(number_text(cell.number))
                                              : nlohmann::json(cell.number);
      else if (cell.kind == Cell::Kind::Text)
        cells[name] = cell.text;
      else {
        cells[name] = nullptr;
        na[name] = cell.text;
      }
    }
    j["rows"].push_back({{"index", r.index}, {"cells", cells}, {"not_available", na}});
  }
  return j;
}

Table table_from_json(const nlohmann::json& j, const std::string& origin) {
  Table t;
  try {
    t.meta = j.at("sweep");
    for (const auto& c : j.at("columns"))
      t.columns.push_back(
          {c.at("name").get<std::string>(),
           c.at("kind").get<std::string>() == "number" ? Column::Kind::Number : Column::Kind::Text,
           c.at("unit").get<std::string>(), c.at("doc").get<std::string>()});
    for (const auto& r : j.at("rows")) {
      Row row;
      row.index = r.at("index").get<std::size_t>();
      for (const Column& c : t.columns) {
        const auto& v = r.at("cells").at(c.name);
        if (v.is_null())
          row.cells.push_back(Cell::na(r.at("not_available").at(c.name).get<std::string>()));
        else if (c.kind == Column::Kind::Text)
          row.cells.push_back(Cell::txt(v.get<std::string>()));
        else if (v.is_string())
          row.cells.push_back(Cell::num(v.get<std::string>() == "inf"
                                            ? std::numeric_limits<double>::infinity()
                                            : -std::numeric_limits<double>::infinity()));
        else
          row.cells.push_back(Cell::num(v.get<double>()));
      }
      t.rows.push_back(std::move(row));
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(origin + ": not a sweep results file (" + e.what() + ")");
  }
  return t;
}

void write_json(const Table& t, const std::string& path) {
  write_json_file(path, to_json(t));
}

Table read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open (expected the results.json of a sweep)");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not JSON (" + e.what() + ")");
  }
  return table_from_json(j, path);
}

Table merge_tables(const std::vector<Table>& shards, const std::vector<std::string>& origins) {
  if (shards.empty()) throw Error("sweep-merge: no results to merge");
  const auto without_shard = [](nlohmann::json m) {
    m.erase("shard");
    return m;
  };
  Table merged;
  merged.meta = without_shard(shards.front().meta);
  merged.columns = shards.front().columns;
  std::map<std::size_t, std::size_t> owner;  // point -> shard that holds it
  for (std::size_t s = 0; s < shards.size(); ++s) {
    if (without_shard(shards[s].meta) != merged.meta)
      throw Error(origins[s] + ": a different sweep from " + origins[0] +
                  " (scene, --set, --vary, truth or --part differ)");
    if (shards[s].columns.size() != merged.columns.size() ||
        !std::equal(merged.columns.begin(), merged.columns.end(), shards[s].columns.begin(),
                    [](const Column& a, const Column& b) { return a.name == b.name; }))
      throw Error(origins[s] + ": its columns differ from " + origins[0] + "'s");
    for (const Row& r : shards[s].rows) {
      const auto [it, fresh] = owner.emplace(r.index, s);
      if (!fresh)
        throw Error(origins[s] + ": point " + std::to_string(r.index) + " is also in " +
                    origins[it->second]);
      merged.rows.push_back(r);
    }
  }
  const std::size_t total = merged.meta.value("points_total", std::size_t{0});
  for (std::size_t i = 0; i < total; ++i)
    if (!owner.count(i))
      throw Error("sweep-merge: point " + std::to_string(i) + " of " + std::to_string(total) +
                  " is in none of the inputs (a shard is missing)");
  if (owner.size() != total || (!owner.empty() && owner.rbegin()->first >= total))
    throw Error("sweep-merge: the inputs hold points beyond the sweep's " + std::to_string(total));
  std::sort(merged.rows.begin(), merged.rows.end(),
            [](const Row& a, const Row& b) { return a.index < b.index; });
  return merged;
}

}  // namespace voxcast::cosim::sweep
