// The results of a sweep as a table: one row per point, in point order, with
// typed columns; its CSV and JSON forms, the Pareto marking, and the merge of
// shards. A pure data layer: nothing here renders.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace voxcast::cosim::sweep {

struct Column {
  enum class Kind { Number, Text };
  std::string name;
  Kind kind = Kind::Number;
  std::string unit;  // "dB", "LSB", "frames/s", ... ("" for none)
  std::string doc;   // one line (docs/sweep.md lists them)
};

// A number, a text, or not available with the reason ("rtl runs only the
// compiled presets ..."). Never an invented value.
struct Cell {
  enum class Kind { Number, Text, NotAvailable };
  Kind kind = Kind::NotAvailable;
  double number = 0.0;
  std::string text;  // the text, or the reason when not available

  static Cell num(double v) { return {Kind::Number, v, {}}; }
  static Cell txt(std::string t) { return {Kind::Text, 0.0, std::move(t)}; }
  static Cell na(std::string reason) { return {Kind::NotAvailable, 0.0, std::move(reason)}; }
  std::optional<double> value() const {
    return kind == Kind::Number ? std::optional<double>(number) : std::nullopt;
  }
  friend bool operator==(const Cell&, const Cell&) = default;
};

struct Row {
  std::size_t index = 0;    // the point's index in the plan
  std::vector<Cell> cells;  // one per column
  friend bool operator==(const Row&, const Row&) = default;
};

struct Table {
  nlohmann::json meta;  // scene, sets, axes, truth, points_total (results.json "sweep")
  std::vector<Column> columns;
  std::vector<Row> rows;  // ascending index

  // The column's position; throws voxcast::Error naming it if absent.
  std::size_t column(const std::string& name) const;
};

// A point's configuration as a plot label: its varied keys' values by their
// last name part, "profile=balanced oversampling=2" (the axes are the
// table's first meta["axes"].size() columns).
std::string point_label(const Table& table, const Row& row);

// --- Pareto ---------------------------------------------------------------------
// Point p dominates q iff p is at least as good as q in every objective and
// strictly better in one. The front is the set of points no other point
// dominates; points equal in every objective are all on it (neither dominates).
struct Objective {
  std::string column;
  bool maximize = true;
};
// For each point (a vector of objective values, nullopt = not available): true
// on the front, false off it, nullopt if any objective is not available (such a
// point neither joins nor blocks the front).
std::vector<std::optional<bool>> pareto_front(
    const std::vector<std::vector<std::optional<double>>>& points,
    const std::vector<bool>& maximize);

// A Pareto marking column of the table (the extension point for more fronts:
// add one to pareto_fronts() in sweep.cpp).
struct Front {
  Column column;  // a Text column: "yes" / "no"
  std::vector<Objective> objectives;
};
// Sets the front's column of every row (cells of rows whose status is not "ok"
// or whose objectives are not available become not available).
void mark_front(Table& table, const Front& front);

// --- Files ----------------------------------------------------------------------
// results.csv: a header of column names, then one line per row; numbers in the
// shortest form that reads back to the same double, "inf" for infinity, an
// empty field when not available (its reason is in the row's `notes` column).
void write_csv(const Table& table, const std::string& path);
// results.json: {"sweep": meta, "columns": [...], "rows": [{"index": i,
// "cells": {name: value or null}, "not_available": {name: reason}}]}.
nlohmann::json to_json(const Table& table);
Table table_from_json(const nlohmann::json& j, const std::string& origin);
void write_json(const Table& table, const std::string& path);
Table read_json(const std::string& path);

// Joins shard tables: the same sweep (meta equal but for "shard"), the same
// columns, no point twice, every point of the plan present. Throws a one-line
// voxcast::Error naming the file and point otherwise. The result has no
// "shard" in its meta, so it equals a single run's table.
Table merge_tables(const std::vector<Table>& shards, const std::vector<std::string>& origins);

}  // namespace voxcast::cosim::sweep
