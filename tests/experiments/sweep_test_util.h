// Helpers for the sweep tests: a fresh temporary folder, files written into it, and the rows of a query on a
// results database as text (reals with 17 significant digits, so "equal" means bit-for-bit equal).
#pragma once

#include <sqlite3.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace cmt::test {

inline std::filesystem::path fresh_dir(const std::string& name) {
  std::string tmpl = (std::filesystem::temp_directory_path() / ("cmt-" + name + "-XXXXXX")).string();
  if (mkdtemp(tmpl.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  return tmpl;
}

inline std::filesystem::path write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

inline std::string source_task(const std::string& name) {
  return std::string(CMT_SOURCE_DIR) + "/models/tasks/" + name + ".yaml";
}

using Rows = std::vector<std::vector<std::string>>;

inline Rows query_rows(const std::filesystem::path& db_path, const std::string& sql) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(db_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    throw std::runtime_error("cannot open " + db_path.string());
  }
  sqlite3_busy_timeout(db, 10000);
  sqlite3_stmt* st = nullptr;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr) != SQLITE_OK) {
    const std::string msg = sqlite3_errmsg(db);
    sqlite3_close(db);
    throw std::runtime_error(db_path.string() + ": " + msg);
  }
  Rows rows;
  while (sqlite3_step(st) == SQLITE_ROW) {
    std::vector<std::string> row;
    for (int c = 0; c < sqlite3_column_count(st); ++c) {
      switch (sqlite3_column_type(st, c)) {
        case SQLITE_NULL:
          row.push_back("NULL");
          break;
        case SQLITE_FLOAT: {
          char buf[64];
          std::snprintf(buf, sizeof buf, "%.17g", sqlite3_column_double(st, c));
          row.push_back(buf);
          break;
        }
        default:
          row.push_back(reinterpret_cast<const char*>(sqlite3_column_text(st, c)));
      }
    }
    rows.push_back(std::move(row));
  }
  sqlite3_finalize(st);
  sqlite3_close(db);
  return rows;
}

inline long long query_count(const std::filesystem::path& db, const std::string& sql) {
  return std::stoll(query_rows(db, sql).at(0).at(0));
}

// Everything about the finished units that must not depend on how the sweep was run (interrupted, sharded,
// MPI, thread count): configurations, verdicts and metrics by unit_key, without timings and row ids.
inline Rows unit_results(const std::filesystem::path& db) {
  return query_rows(
      db,
      "SELECT c.unit_key, c.task, c.strategy, c.params, c.n, c.seed, c.mode, c.status, c.task_yaml, "
      "p.reliable, p.failure, m.rollouts, m.successes, m.unstable, m.ends, m.outside, m.soundness, "
      "m.coverage, m.coverage_radius, m.contact_tolerance, m.soundness_bug, m.counterexample, "
      "m.sticking FROM configs c JOIN predictions p ON p.config_id = c.config_id JOIN metrics m ON "
      "m.config_id = c.config_id ORDER BY c.unit_key");
}

inline Rows rollout_results(const std::filesystem::path& db) {
  return query_rows(
      db,
      "SELECT c.unit_key, r.rollout, r.motion, r.start_x, r.start_y, r.start_z, r.end_x, r.end_y, "
      "r.end_z, r.atom, r.termination, r.inside, r.distance, r.success, r.unstable FROM rollouts r "
      "JOIN configs c ON c.config_id = r.config_id ORDER BY c.unit_key, r.rollout, r.motion");
}

}  // namespace cmt::test
