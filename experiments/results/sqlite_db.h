// A small RAII layer over the SQLite C API for the results store (read-write) and the report (read-only): a
// connection and prepared statements that finalize themselves, every error turned into SqliteError naming the
// database file and SQLite's message.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

struct sqlite3;
struct sqlite3_stmt;

namespace cmt {

class SqliteStatement;

// what(): "<path>: <context>: <SQLite's message>" (no context: "<path>: <message>"); the parts apart for
// callers that key their own errors (the report's InputError by table).
class SqliteError : public std::runtime_error {
 public:
  SqliteError(std::string path, std::string context, std::string detail);
  const std::string& path() const { return path_; }
  const std::string& context() const { return context_; }
  const std::string& detail() const { return detail_; }  // SQLite's message

 private:
  std::string path_, context_, detail_;
};

class SqliteDb {
 public:
  enum class Mode { kReadWrite, kReadOnly };
  // kReadWrite opens the file, creating it if needed; kReadOnly opens an existing file and never writes (a
  // report made while a sweep is still writing).
  explicit SqliteDb(const std::filesystem::path& path, Mode mode = Mode::kReadWrite);
  ~SqliteDb();
  SqliteDb(const SqliteDb&) = delete;
  SqliteDb& operator=(const SqliteDb&) = delete;

  void exec(const std::string& sql);  // one or more statements without parameters
  SqliteStatement prepare(const std::string& sql);
  std::int64_t last_insert_rowid() const;
  const std::string& path() const { return path_; }
  sqlite3* handle() const { return db_; }
  [[noreturn]] void fail(const std::string& what) const;

 private:
  sqlite3* db_ = nullptr;
  std::string path_;
};

class SqliteStatement {
 public:
  SqliteStatement(SqliteDb& db, const std::string& sql);
  ~SqliteStatement();
  SqliteStatement(SqliteStatement&& other) noexcept;
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;
  SqliteStatement& operator=(SqliteStatement&&) = delete;

  // Parameters are 1-based, as in SQLite.
  SqliteStatement& bind(int i, std::int64_t v);
  SqliteStatement& bind(int i, int v) { return bind(i, static_cast<std::int64_t>(v)); }
  SqliteStatement& bind(int i, bool v) { return bind(i, static_cast<std::int64_t>(v ? 1 : 0)); }
  SqliteStatement& bind(int i, double v);
  SqliteStatement& bind(int i, const std::string& v);
  SqliteStatement& bind(int i, const char* v) { return bind(i, std::string(v)); }
  SqliteStatement& bind_null(int i);
  template <class T>
  SqliteStatement& bind(int i, const std::optional<T>& v) {
    return v ? bind(i, *v) : bind_null(i);
  }

  bool step();   // true while a row is available
  void run();    // steps a statement that returns no rows
  void reset();  // for reuse with new bindings

  int columns() const;
  bool is_null(int col) const;
  bool is_integer(int col) const;
  bool is_real(int col) const;
  std::int64_t integer(int col) const;  // 0-based columns
  double real(int col) const;
  std::string text(int col) const;
  std::string column_name(int col) const;

 private:
  SqliteDb* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

// BEGIN IMMEDIATE (takes the write lock at once, so two writers never deadlock upgrading read locks) ...
// COMMIT; rolled back by the destructor unless commit() ran.
class SqliteTransaction {
 public:
  explicit SqliteTransaction(SqliteDb& db);
  ~SqliteTransaction();
  SqliteTransaction(const SqliteTransaction&) = delete;
  SqliteTransaction& operator=(const SqliteTransaction&) = delete;
  void commit();

 private:
  SqliteDb& db_;
  bool open_ = true;
};

}  // namespace cmt
