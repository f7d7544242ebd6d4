/* Test library without RegisterPlugin: the loader's "Failed to resolve RegisterPlugin". */
int car_test_not_a_plugin(void) { return 1; }
