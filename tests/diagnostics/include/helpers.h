// Helpers for the diagnostics corpus (found through -I tests/diagnostics/include).
#ifndef HELPERS_H
#define HELPERS_H
float helper_scale(float x) { return 2 * x; }
#endif
