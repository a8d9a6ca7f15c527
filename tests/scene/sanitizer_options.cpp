// Default sanitizer options of scene_asan_tests. ctest also sets ASAN_OPTIONS for each test
// (tests/scene/CMakeLists.txt); UBSAN_OPTIONS is set here because gtest_discover_tests can pass
// only one ENVIRONMENT entry per test. Variables set in the environment take precedence.
extern "C" const char* __asan_default_options() {
    return "halt_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1";
}
extern "C" const char* __ubsan_default_options() { return "halt_on_error=1:print_stacktrace=1"; }
