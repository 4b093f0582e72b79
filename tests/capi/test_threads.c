/* Distinct handles may be used concurrently (wefm.h "Threads"): faces solved at the same time from two
 * threads give the same UVs, bit for bit, as the same faces solved one after the other; the
 * thread-local message of one thread is not touched by failures in another. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <wefm/wefm.h>

typedef struct {
  int64_t nv, nt;
  double* xyz;
  int32_t* tri;
} mesh_t;

typedef struct {
  const mesh_t* mesh;
  double s;
  double* uv;
  int64_t count;
  wefm_status status;
  int message_ok;
  int slot; /* which thread: each fails a different call, to tell the thread-local messages apart */
  pthread_barrier_t* start;
} job_t;

/* A doubly curved (n+1) x (n+1) grid patch: not developable, so each solve iterates for a while. */
static mesh_t bumpy(int n, double amplitude) {
  mesh_t m;
  int i, j, k = 0;
  m.nv = (int64_t)(n + 1) * (n + 1);
  m.nt = 2 * (int64_t)n * n;
  m.xyz = malloc(sizeof(double) * 3 * (size_t)m.nv);
  m.tri = malloc(sizeof(int32_t) * 3 * (size_t)m.nt);
  for (i = 0; i <= n; ++i)
    for (j = 0; j <= n; ++j) {
      const double u = (double)j / n, v = (double)i / n;
      double* p = m.xyz + 3 * (i * (n + 1) + j);
      p[0] = u, p[1] = v, p[2] = amplitude * sin(2.0 * u) * cos(3.0 * v);
    }
  for (i = 0; i < n; ++i)
    for (j = 0; j < n; ++j) {
      const int32_t a = i * (n + 1) + j, b = a + 1, c = a + n + 2, d = a + n + 1;
      int32_t* t = m.tri + 6 * k++;
      t[0] = a, t[1] = b, t[2] = c, t[3] = a, t[4] = c, t[5] = d;
    }
  return m;
}

static void* solve_job(void* arg) {
  job_t* job = arg;
  wefm_face* face = NULL;
  wefm_options o;
  const char* own = job->slot == 0 ? "wefm_face_solve" : "wefm_face_build";
  if (job->start) pthread_barrier_wait(job->start);
  /* A failure without a handle in this thread: the message is this thread's alone. */
  job->message_ok = (job->slot == 0 ? wefm_face_solve(NULL) : wefm_face_build(NULL)) == WEFM_ERROR_NULL_ARGUMENT;
  job->status = wefm_face_create(&face);
  if (job->status == WEFM_OK) job->status = wefm_face_set_mesh(face, job->mesh->nv, job->mesh->xyz, job->mesh->nt, job->mesh->tri);
  wefm_options_init(&o, sizeof o);
  o.s = job->s;
  if (job->status == WEFM_OK) job->status = wefm_face_set_options(face, &o);
  if (job->status == WEFM_OK) job->status = wefm_face_solve(face);
  if (job->status == WEFM_OK) job->status = wefm_face_get_uv(face, NULL, 0, &job->count);
  if (job->status == WEFM_OK) {
    job->uv = malloc(sizeof(double) * (size_t)job->count);
    job->status = wefm_face_get_uv(face, job->uv, job->count, &job->count);
  }
  if (job->status != WEFM_OK) fprintf(stderr, "solve: %s: %s\n", wefm_status_string(job->status), wefm_face_last_error(face));
  job->message_ok = job->message_ok && strstr(wefm_last_error(), own) != NULL;
  wefm_face_release(face);
  return NULL;
}

int main(void) {
  mesh_t meshes[2];
  job_t reference[2], concurrent[2];
  pthread_t threads[2];
  pthread_barrier_t start;
  int round, k, failures = 0;

  meshes[0] = bumpy(24, 0.3);
  meshes[1] = bumpy(20, 0.5);
  for (k = 0; k < 2; ++k) {
    memset(&reference[k], 0, sizeof reference[k]);
    reference[k].mesh = &meshes[k];
    reference[k].s = k == 0 ? 1.0 : 0.5;
    reference[k].slot = k;
    solve_job(&reference[k]);
    if (reference[k].status != WEFM_OK) return 1;
  }
  pthread_barrier_init(&start, NULL, 2);
  /* Both pairings: different faces at once, and the same face twice at once. */
  for (round = 0; round < 4; ++round) {
    for (k = 0; k < 2; ++k) {
      const int which = round % 2 == 0 ? k : round / 2 % 2;
      concurrent[k] = reference[which];
      concurrent[k].uv = NULL;
      concurrent[k].start = &start;
      concurrent[k].slot = k;
      pthread_create(&threads[k], NULL, solve_job, &concurrent[k]);
    }
    for (k = 0; k < 2; ++k) pthread_join(threads[k], NULL);
    for (k = 0; k < 2; ++k) {
      const job_t* ref = &reference[round % 2 == 0 ? k : round / 2 % 2];
      const int same = concurrent[k].status == WEFM_OK && concurrent[k].count == ref->count &&
                       memcmp(concurrent[k].uv, ref->uv, sizeof(double) * (size_t)ref->count) == 0;
      if (!same) {
        ++failures;
        fprintf(stderr, "round %d thread %d: UVs differ from the sequential solve\n", round, k);
      }
      if (!concurrent[k].message_ok) {
        ++failures;
        fprintf(stderr, "round %d thread %d: wefm_last_error() was not this thread's message\n", round, k);
      }
      free(concurrent[k].uv);
    }
  }
  pthread_barrier_destroy(&start);
  printf("%lld + %lld UV values, 4 concurrent rounds: %s\n", (long long)reference[0].count,
         (long long)reference[1].count, failures ? "FAILED" : "bit-identical to sequential");
  for (k = 0; k < 2; ++k) free(reference[k].uv), free(meshes[k].xyz), free(meshes[k].tri);
  return failures ? 1 : 0;
}
