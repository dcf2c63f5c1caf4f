// The look at a model file's size and nesting before the XML parser reads it (learning/model_file_check.hpp).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "culling/model_file_check.hpp"

namespace {

namespace fs = std::filesystem;
using clothcd::learning::check_model_file_shape;
using clothcd::learning::kMaxModelFileBytes;
using clothcd::learning::kMaxModelNesting;

std::string write(const std::string& name, const std::string& text) {
  const std::string path = (fs::temp_directory_path() / ("clothcd_model_shape_" + name + ".xml")).string();
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  return path;
}

std::string nested(int levels, const std::string& inner = "") {
  std::string text;
  for (int i = 0; i < levels; ++i) text += "<e>";
  text += inner;
  for (int i = 0; i < levels; ++i) text += "</e>";
  return text;
}

}  // namespace

TEST_CASE("model files nested up to the limit pass, deeper ones are refused", "[learning][model-file]") {
  CHECK_NOTHROW(check_model_file_shape(write("at_limit", "<?xml version=\"1.0\"?>\n" + nested(kMaxModelNesting))));
  CHECK_THROWS_WITH(check_model_file_shape(write("beyond", nested(kMaxModelNesting + 1))),
                    Catch::Contains("nested more than"));
  // Unclosed tags count as well (a truncated deep file must not reach the parser either).
  std::string unclosed;
  for (int i = 0; i < 10 * kMaxModelNesting; ++i) unclosed += "<e a='1'>";
  CHECK_THROWS_WITH(check_model_file_shape(write("unclosed", unclosed)), Catch::Contains("nested more than"));
}

TEST_CASE("the nesting scan skips what is not an element", "[learning][model-file]") {
  std::string siblings;
  for (int i = 0; i < 10 * kMaxModelNesting; ++i) siblings += "<e/><f x=\"a>b\" />";
  const std::string markup_in_text = "<!-- " + nested(10 * kMaxModelNesting) + " --><![CDATA[" +
                                     nested(10 * kMaxModelNesting) + "]]><!DOCTYPE x><?pi <a><a>?>";
  CHECK_NOTHROW(check_model_file_shape(write("siblings", "<r>" + siblings + "</r>")));
  CHECK_NOTHROW(check_model_file_shape(write("markup", "<r>" + markup_in_text + "</r>")));
  CHECK_NOTHROW(check_model_file_shape(write("unterminated", nested(3) + "<e attr='>")));
  CHECK_NOTHROW(check_model_file_shape("/nonexistent/network.xml"));  // the parser reports it
}

TEST_CASE("model files larger than any model are refused without being read", "[learning][model-file]") {
  const std::string path = (fs::temp_directory_path() / "clothcd_model_shape_huge.xml").string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.seekp(kMaxModelFileBytes);  // sparse where the file system allows it
    out.put('<');
  }
  CHECK_THROWS_WITH(check_model_file_shape(path), Catch::Contains("larger than any model"));
  fs::remove(path);
}
