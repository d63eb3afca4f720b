#pragma once
// The BLAS under CHOLMOD's supernodal factorization may start its own threads (OpenBLAS does,
// one per core). grip parallelizes across environments instead, so it asks for one BLAS
// thread: no oversubscription, and the same floating-point operations whatever the thread
// count.
namespace grip::solver {

// Sets the BLAS to one thread if it is a threaded BLAS grip knows (OpenBLAS); else does
// nothing. Safe to call more than once.
void use_single_threaded_blas();

}  // namespace grip::solver
