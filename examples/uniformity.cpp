// examples/uniformity.cpp -- the smallest program using the installed
// uniparam library: parse a rational curve, measure how far its parameter is
// from uniform angular speed, print mu and u to 20 digits.
//
//   uniformity                 # the curve (t, t^2)
//   uniformity "(t, t^3)"      # any curve in the parser's syntax
#include <uniparam/uniparam.hpp>

#include <exception>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  namespace up = uniparam::api;
  const std::string text = argc > 1 ? argv[1] : "(t, t^2)";
  try {
    up::Options o;
    o.digits = 20;
    const up::Curve c = up::Curve::parse(text, o);
    const up::Uniformity r = up::uniformity(c, o);
    std::cout << "curve = " << text << "\n";
    std::cout << "mu = " << r.mu.str(o.digits) << "\n";
    std::cout << "u = " << r.u.str(o.digits) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "uniformity: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
