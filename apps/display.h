#pragma once
// Debian's VTK renders only through X. A command calls ensure_display() just before it first
// renders: with no DISPLAY it runs the same command line again under a virtual X server
// (xvfb-run) and does not return; see docs/rendering.md.
namespace rbcflow::cli {

void ensure_display();

}  // namespace rbcflow::cli
