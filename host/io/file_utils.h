#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace mcquad {

//! Whole file as bytes; InputError naming the file when it cannot be read.
std::string read_file(const std::string& path);

//! A file mapped read-only into memory: readers parse it in place, so a
//! large cloud is never copied into a buffer first. InputError naming the
//! file when it cannot be opened.
class MappedFile {
 public:
  explicit MappedFile(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::string_view view() const { return {static_cast<const char*>(data_), size_}; }
  //! Drops the pages wholly before `offset` from this process's memory (a
  //! reader done with them; the view stays valid and would read them
  //! again). Keeps a 2.4 GB cloud file from doubling the peak memory of
  //! reading it.
  void release_before(size_t offset) const;

 private:
  void* data_ = nullptr;
  size_t size_ = 0;
};

//! Lower-case extension without the dot ("ply"), or "" when there is none.
std::string file_extension(const std::string& path);

//! Writes through `write_to(temporary_path)` into a temporary file beside
//! `path`, then renames it over `path`, so a failure never leaves a
//! half-written file. The temporary keeps `path`'s extension (writers choose
//! the format by extension). OutputError naming `path` on any failure.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write_to);

//! Writes `text` to `path` atomically.
void write_text_atomically(const std::string& path, const std::string& text);

//! Splits a line into fields separated by whitespace and/or commas.
std::vector<std::string_view> split_fields(std::string_view line);

//! Parses a whole field as a finite or non-finite float/double; false if it
//! is not a number.
bool parse_number(std::string_view field, double& value);
bool parse_integer(std::string_view field, long long& value);

//! Calls `visit(line_number, line)` for every line (1-based), without the
//! line terminator; handles \n and \r\n.
void for_each_line(std::string_view text, const std::function<void(size_t, std::string_view)>& visit);

}  // namespace mcquad
