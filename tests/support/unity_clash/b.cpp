// A fixture of ctest tests.unity_names_finds_a_clash (never compiled): see a.cpp.
namespace {

double spacing(double h) {
    return 0.25 * h;
}

} // namespace
