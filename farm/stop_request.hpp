#pragma once
// SIGINT and SIGTERM ask a farm run to stop: the work units in flight finish and are committed,
// then the run exits, and `grip farm JOB --resume` continues it. A second signal exits at
// once (the journal still lets a resume lose nothing committed).
namespace grip::farm {

// Installs the handlers for this process's lifetime (idempotent).
void install_stop_handlers();
bool stop_requested();

}  // namespace grip::farm
