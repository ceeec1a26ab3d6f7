#pragma once
// Ctrl-C (SIGINT) and SIGTERM during a long command: the first one asks the loop to stop after
// the frame in progress (every file is complete, written then renamed); a second one exits.
namespace masav::app {

void install_interrupt_handler();
bool interrupted();

}  // namespace masav::app
