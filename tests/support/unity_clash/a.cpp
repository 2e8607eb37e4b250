// A fixture of ctest tests.unity_names_finds_a_clash (never compiled): with b.cpp, two files of
// one executable that each define `spacing` at namespace scope, with different signatures, so a
// unity build of both would compile and b.cpp's call could take this one.
namespace {

double spacing(float h) {
    return 0.5 * h;
}

} // namespace
