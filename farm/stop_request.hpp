#pragma once
// SIGINT and SIGTERM ask a farm run to stop: the work units in flight finish and are committed,
// then the run exits, and `grip farm JOB --resume` continues it. A second signal exits at
// once (the journal still lets a resume lose nothing committed).
namespace grip::farm {

// Installs the handlers for this process's lifetime (idempotent).
void install_stop_handlers();
// Under mpirun: this rank is killed (SIGKILL) when its launcher, its parent process (mpirun or
// the node's daemon), dies. Ranks that commit their own work units never wait for each other, so
// nothing else would stop the ranks of a killed mpirun before the job's end (each holding the
// journal's lock, a resume refused meanwhile). Elsewhere (no mpirun) nothing changes.
void end_with_launcher();
bool stop_requested();
// While set, a stop signal ends the process at once (exit 128 + signal): before the dataset is
// created or reopened for writing (reading the job, planning) there is nothing to commit, and
// planning a large job may take hours before its first trial.
void stop_at_once(bool yes);

}  // namespace grip::farm
