#pragma once
// The libraries under CHOLMOD's supernodal factorization may start threads of their own: the
// BLAS (OpenBLAS starts one per core) and CHOLMOD itself, whose OpenMP loops ask for a team of
// a size fixed when it was compiled (4 in Debian's), whatever OMP_NUM_THREADS says. grip
// parallelizes across environments instead (--threads), so it keeps both to the calling
// thread: no oversubscription, no threads waking and sleeping around every supernode, and the
// same floating-point operations whatever the thread count.
namespace grip::solver {

// Sets the BLAS to one thread if it is a threaded BLAS grip knows (OpenBLAS); else does
// nothing. Safe to call more than once.
void use_single_threaded_blas();

// Makes every OpenMP parallel region the calling thread starts run on that thread alone (no
// active parallel level), if an OpenMP runtime is loaded; else does nothing. Cheap: call it
// before each factorization, on the thread that factorizes.
void use_single_threaded_openmp();

}  // namespace grip::solver
