#include "app/interrupt.h"

#include <unistd.h>

#include <csignal>
#include <cstdlib>

namespace masav::app {
namespace {

volatile std::sig_atomic_t g_interrupts = 0;

void on_signal(int) {
  if (g_interrupts > 0) _exit(130);
  g_interrupts = g_interrupts + 1;
}

}  // namespace

void install_interrupt_handler() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

bool interrupted() {
  return g_interrupts > 0;
}

}  // namespace masav::app
