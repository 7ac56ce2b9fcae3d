/* Linked into every program of a sanitizer build (PENUMBRA_SANITIZERS) only: dlclose does nothing.
 * The Vulkan loader unloads the driver (lavapipe) and the validation layer at vkDestroyInstance;
 * LeakSanitizer reports at exit, when their allocations then sit in an "<unknown module>" that no
 * suppression can name. With the modules kept, tests/lsan.supp names them (third-party libraries
 * only; Penumbra's own leaks always fail). */
int dlclose(void* handle) {
    (void)handle;
    return 0;
}
