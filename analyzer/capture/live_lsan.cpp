// libsigrok 0.5.2 leaks a few hundred bytes of its drivers' scan results and of a loaded
// session, allocated through glib, whose frames the sanitizer's fast unwinder cannot see
// past: the AddressSanitizer build is told so, quietly, and its leak check stays on for ours.
#if defined(__SANITIZE_ADDRESS__)
extern "C" const char* __lsan_default_suppressions() {
    return "leak:g_malloc\nleak:g_malloc0\nleak:g_malloc_n\nleak:g_malloc0_n\nleak:g_realloc\n"
           "leak:g_try_malloc\nleak:libsigrok.so\n";
}
extern "C" const char* __lsan_default_options() {
    return "print_suppressions=0";
}
#endif
