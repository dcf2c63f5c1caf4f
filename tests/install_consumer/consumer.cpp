// Uses the installed library: generates the paper's cloth C and prints its triangle count (4802).
#include <clothcd/mesh/mesh_generators.hpp>
#include <iostream>

int main() { std::cout << clothcd::make_paper_cloth('C').face_count() << '\n'; }
