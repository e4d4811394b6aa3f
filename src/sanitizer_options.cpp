// Compiled into every sphclip target of the sanitizer build only
// (SPHCLIP_SANITIZE=ON). Mesa's GL drivers keep allocations until the process
// ends, some made by JIT-compiled code that no leak suppression can match, so
// leak detection is off; AddressSanitizer's memory errors and UBSan stay on.
extern "C" const char* __asan_default_options() {
    return "detect_leaks=0";
}
