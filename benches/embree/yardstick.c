/* Embree as a yardstick, Embree's half (issue 39, item 4): traces the ray
 * sets that `cargo run --release --example embree_yardstick -- dump OUT`
 * wrote through Embree 3, one thread, and writes its answers and times
 * beside ptsc's (file formats: examples/embree_yardstick.rs). Run by
 * scripts/embree-yardstick.sh; not part of CI.
 *
 *   cc -O2 -o yardstick benches/embree/yardstick.c -lembree3
 *   yardstick OUT/SCENE QUALITY RUNS [SET...]
 *
 * QUALITY: high, medium or low (RTC_BUILD_QUALITY_*), with "-user" (e.g.
 * high-user) for the spheres as user geometry.
 *
 * The scene: one triangle mesh (shared vertex and index buffers) and the
 * spheres as RTC_GEOMETRY_TYPE_SPHERE_POINT (a real sphere, hit from
 * outside and inside, as ptsc's) or as user geometry, default scene flags
 * (not robust, not compact), the given build quality. Times rtcIntersect1
 * and rtcOccluded1 over each set: the median of RUNS passes after one
 * untimed pass, in the thread's CPU time (wall time beside it). Writes
 * OUT/SCENE/embree-QUALITY.tsv and SET.embree-QUALITY.{closest,any}. */

#define _POSIX_C_SOURCE 200112L
#include <embree3/rtcore.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

static void fail(const char *what, const char *detail) {
  fprintf(stderr, "yardstick: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
  exit(2);
}

static void on_error(void *user, enum RTCError code, const char *message) {
  (void)user;
  fprintf(stderr, "yardstick: embree error %d: %s\n", (int)code, message);
  exit(2);
}

/* Bytes Embree holds now and at most (its memory monitor). */
static long long held, peak;

static bool on_memory(void *user, ssize_t bytes, bool post) {
  (void)user;
  (void)post;
  held += bytes;
  if (held > peak)
    peak = held;
  return true;
}

/* Seconds of `clock`: the thread's CPU time for the traversal, the
 * process's for the build (whichever thread Embree builds on), as the Rust
 * half times; wall time also counts the waits for a core on a shared
 * machine. */
static double seconds(clockid_t clock) {
  struct timespec ts;
  clock_gettime(clock, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int by_value(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *t, int n) {
  qsort(t, n, sizeof *t, by_value);
  return t[n / 2];
}

/* The whole of `path`, its size in `size`. */
static unsigned char *slurp(const char *path, size_t *size) {
  FILE *f = fopen(path, "rb");
  if (!f)
    fail("cannot open", path);
  fseek(f, 0, SEEK_END);
  *size = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char *b = malloc(*size ? *size : 1);
  if (!b || fread(b, 1, *size, f) != *size)
    fail("cannot read", path);
  fclose(f);
  return b;
}

static void spit(const char *path, const void *data, size_t size) {
  FILE *f = fopen(path, "wb");
  if (!f || fwrite(data, 1, size, f) != size || fclose(f))
    fail("cannot write", path);
}

typedef struct {
  uint32_t vertices, triangles, spheres;
  float *vertex;   /* 4 floats a vertex: Embree reads 16 bytes at a time */
  uint32_t *index; /* 3 a triangle */
  uint32_t *triangle_prim;
  float *sphere; /* centre and radius */
  uint32_t *sphere_prim;
} Geometry;

static Geometry load_geometry(const char *path) {
  size_t size;
  unsigned char *b = slurp(path, &size);
  Geometry g;
  if (size < 20 || memcmp(b, "PTSYGEO1", 8))
    fail("not a geometry file", path);
  memcpy(&g.vertices, b + 8, 4);
  memcpy(&g.triangles, b + 12, 4);
  memcpy(&g.spheres, b + 16, 4);
  size_t want = 20 + 12 * (size_t)g.vertices + 16 * (size_t)g.triangles + 20 * (size_t)g.spheres;
  if (size != want)
    fail("geometry file of the wrong size", path);
  const unsigned char *p = b + 20;
  /* Embree aligns the buffers it is given to 16 bytes. */
  g.vertex = aligned_alloc(16, 16 * ((size_t)g.vertices + 1));
  for (uint32_t i = 0; i < g.vertices; i++, p += 12) {
    memcpy(g.vertex + 4 * i, p, 12);
    g.vertex[4 * i + 3] = 0;
  }
  g.index = aligned_alloc(16, 12 * ((size_t)g.triangles + 1));
  memcpy(g.index, p, 12 * (size_t)g.triangles);
  p += 12 * (size_t)g.triangles;
  g.triangle_prim = malloc(4 * ((size_t)g.triangles + 1));
  memcpy(g.triangle_prim, p, 4 * (size_t)g.triangles);
  p += 4 * (size_t)g.triangles;
  g.sphere = aligned_alloc(16, 16 * ((size_t)g.spheres + 1));
  memcpy(g.sphere, p, 16 * (size_t)g.spheres);
  p += 16 * (size_t)g.spheres;
  g.sphere_prim = malloc(4 * ((size_t)g.spheres + 1));
  memcpy(g.sphere_prim, p, 4 * (size_t)g.spheres);
  free(b);
  return g;
}

/* Geometry ids: the mesh first, then the spheres. */
enum { MESH = 0, SPHERES = 1 };

/* Spheres as Embree's own RTC_GEOMETRY_TYPE_SPHERE_POINT, or as user
 * geometry tested with ptsc's formula (src/geometry/sphere.rs: the
 * discriminant from the perpendicular distance, Ray Tracing Gems ch. 7),
 * called back by Embree's traversal. */
static int user_spheres;

static void sphere_bounds(const struct RTCBoundsFunctionArguments *args) {
  const float *s = (const float *)args->geometryUserPtr + 4 * args->primID;
  struct RTCBounds *b = args->bounds_o;
  b->lower_x = s[0] - s[3], b->lower_y = s[1] - s[3], b->lower_z = s[2] - s[3];
  b->upper_x = s[0] + s[3], b->upper_y = s[1] + s[3], b->upper_z = s[2] + s[3];
}

/* The hit distance of ray (o, d) with sphere s in (tnear, tfar), or NAN. */
static float sphere_hit(const float *s, const float o[3], const float d[3], float tnear,
                        float tfar) {
  float oc[3] = {o[0] - s[0], o[1] - s[1], o[2] - s[2]};
  float a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  float b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
  float perp[3] = {oc[0] - b / a * d[0], oc[1] - b / a * d[1], oc[2] - b / a * d[2]};
  float disc = s[3] * s[3] - (perp[0] * perp[0] + perp[1] * perp[1] + perp[2] * perp[2]);
  if (disc < 0)
    return NAN;
  float sq = sqrtf(a * disc);
  float q = -(b + copysignf(sq, b));
  float c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - s[3] * s[3];
  float t0 = q / a, t1 = q != 0 ? c / q : 0;
  if (t0 > t1) {
    float t = t0;
    t0 = t1, t1 = t;
  }
  if (t0 > tnear && t0 < tfar)
    return t0;
  if (t1 > tnear && t1 < tfar)
    return t1;
  return NAN;
}

static void sphere_intersect(const struct RTCIntersectFunctionNArguments *args) {
  /* rtcIntersect1 calls back with one ray. */
  if (!args->valid[0])
    return;
  struct RTCRayHit *rh = (struct RTCRayHit *)args->rayhit;
  const float *s = (const float *)args->geometryUserPtr + 4 * args->primID;
  float o[3] = {rh->ray.org_x, rh->ray.org_y, rh->ray.org_z};
  float d[3] = {rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z};
  float t = sphere_hit(s, o, d, rh->ray.tnear, rh->ray.tfar);
  if (isnan(t))
    return;
  rh->ray.tfar = t;
  rh->hit.Ng_x = o[0] + t * d[0] - s[0];
  rh->hit.Ng_y = o[1] + t * d[1] - s[1];
  rh->hit.Ng_z = o[2] + t * d[2] - s[2];
  rh->hit.u = rh->hit.v = 0;
  rh->hit.primID = args->primID;
  rh->hit.geomID = args->geomID;
  rh->hit.instID[0] = args->context->instID[0];
}

static void sphere_occluded(const struct RTCOccludedFunctionNArguments *args) {
  if (!args->valid[0])
    return;
  struct RTCRay *r = (struct RTCRay *)args->ray;
  const float *s = (const float *)args->geometryUserPtr + 4 * args->primID;
  float o[3] = {r->org_x, r->org_y, r->org_z};
  float d[3] = {r->dir_x, r->dir_y, r->dir_z};
  if (!isnan(sphere_hit(s, o, d, r->tnear, r->tfar)))
    r->tfar = -INFINITY;
}

/* Gives the geometry its build quality, commits it and attaches it to the
 * scene under `id`; the scene keeps the only reference. */
static void attach(RTCScene scene, RTCGeometry geometry, enum RTCBuildQuality quality,
                   unsigned id) {
  rtcSetGeometryBuildQuality(geometry, quality);
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(scene, geometry, id);
  rtcReleaseGeometry(geometry);
}

static RTCScene build(RTCDevice device, const Geometry *g, enum RTCBuildQuality quality) {
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, quality);
  if (g->triangles) {
    RTCGeometry m = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(m, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, g->vertex, 0, 16,
                               g->vertices);
    rtcSetSharedGeometryBuffer(m, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, g->index, 0, 12,
                               g->triangles);
    attach(scene, m, quality, MESH);
  }
  if (g->spheres && user_spheres) {
    RTCGeometry s = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(s, g->spheres);
    rtcSetGeometryUserData(s, g->sphere);
    rtcSetGeometryBoundsFunction(s, sphere_bounds, NULL);
    rtcSetGeometryIntersectFunction(s, sphere_intersect);
    rtcSetGeometryOccludedFunction(s, sphere_occluded);
    attach(scene, s, quality, SPHERES);
  } else if (g->spheres) {
    RTCGeometry s = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    rtcSetSharedGeometryBuffer(s, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, g->sphere, 0, 16,
                               g->spheres);
    attach(scene, s, quality, SPHERES);
  }
  rtcCommitScene(scene);
  return scene;
}

typedef struct {
  float o[3], tnear, d[3], tfar;
} Ray;

int main(int argc, char **argv) {
  if (argc < 4)
    fail("usage: yardstick OUT/SCENE QUALITY[-user] RUNS [SET...]", NULL);
  const char *dir = argv[1], *quality_name = argv[2];
  int runs = atoi(argv[3]);
  if (runs < 1)
    fail("RUNS must be at least 1", argv[3]);
  /* QUALITY, or QUALITY-user for spheres as user geometry. */
  char base[16];
  snprintf(base, sizeof base, "%s", quality_name);
  char *dash = strchr(base, '-');
  if (dash && !strcmp(dash, "-user"))
    user_spheres = 1, *dash = 0;
  enum RTCBuildQuality quality;
  if (!strcmp(base, "high"))
    quality = RTC_BUILD_QUALITY_HIGH;
  else if (!strcmp(base, "medium"))
    quality = RTC_BUILD_QUALITY_MEDIUM;
  else if (!strcmp(base, "low"))
    quality = RTC_BUILD_QUALITY_LOW;
  else
    fail("quality is high, medium or low, with -user for user-geometry spheres", quality_name);
#if defined(__SSE__)
  /* Denormals flushed (FTZ, DAZ), as Embree asks of every thread that
   * traces (its verbose device warns otherwise). */
  if (!getenv("YARDSTICK_NO_FTZ"))
    _mm_setcsr(_mm_getcsr() | 0x8040);
#endif
  static const char *default_sets[] = {"camera", "diffuse", "random"};
  const char **sets = argc > 4 ? (const char **)argv + 4 : default_sets;
  int nsets = argc > 4 ? argc - 4 : 3;

  char path[4096], rows[1 << 16];
  size_t used = 0;
#define ROW(...) used += snprintf(rows + used, sizeof rows - used, __VA_ARGS__)

  snprintf(path, sizeof path, "%s/geometry.bin", dir);
  Geometry g = load_geometry(path);
  /* One thread, as ptsc's side: the build as well as the traversal. */
  RTCDevice device = rtcNewDevice(getenv("YARDSTICK_EMBREE_CONFIG") ? getenv("YARDSTICK_EMBREE_CONFIG")
                                                                  : "threads=1");
  if (!device)
    fail("rtcNewDevice failed", NULL);
  rtcSetDeviceErrorFunction(device, on_error, NULL);
  rtcSetDeviceMemoryMonitorFunction(device, on_memory, NULL);

  /* The first build's memory; the median of three builds' times. */
  RTCScene scene = NULL;
  double build_times[3];
  long long bvh_bytes = 0, build_peak = 0;
  for (int i = 0; i < 3; i++) {
    if (scene)
      rtcReleaseScene(scene);
    long long before = held;
    peak = held;
    double start = seconds(CLOCK_PROCESS_CPUTIME_ID);
    scene = build(device, &g, quality);
    build_times[i] = seconds(CLOCK_PROCESS_CPUTIME_ID) - start;
    if (i == 0) {
      bvh_bytes = held - before;
      build_peak = peak - before;
    }
  }
  double build_s = median(build_times, 3);
  ROW("note\tEmbree %s, build quality %s, spheres as %s, threads=1, default scene flags, FTZ/DAZ "
      "%s; medians of %d, the thread's CPU time\n",
      RTC_VERSION_STRING, base, user_spheres ? "user geometry" : "SPHERE_POINT",
      getenv("YARDSTICK_NO_FTZ") ? "off" : "on", runs);
  ROW("build\t%.6f\n", build_s);
  ROW("bytes\tbvh\t%lld\n", bvh_bytes);
  ROW("bytes\tpeak\t%lld\n", build_peak);
  ROW("bytes\tbuffers\t%llu\n",
      16ull * g.vertices + 12ull * g.triangles + 16ull * g.spheres);
  fprintf(stderr, "%s: Embree %s build %.3f s, %lld bytes (peak %lld)\n", dir, quality_name,
          build_s, bvh_bytes, build_peak);

  struct RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  double *times = malloc(sizeof(double) * runs), *walls = malloc(sizeof(double) * runs);
  for (int s = 0; s < nsets; s++) {
    size_t size;
    snprintf(path, sizeof path, "%s/%s.rays", dir, sets[s]);
    unsigned char *b = slurp(path, &size);
    uint32_t n;
    if (size < 12 || memcmp(b, "PTSYRAY1", 8))
      fail("not a ray file", path);
    memcpy(&n, b + 8, 4);
    if (size != 12 + 32 * (size_t)n)
      fail("ray file of the wrong size", path);
    Ray *rays = malloc(32 * (size_t)n + 1);
    memcpy(rays, b + 12, 32 * (size_t)n);
    free(b);

    /* Closest hits: distance and ptsc's primitive, as ptsc writes them. */
    struct {
      float t;
      uint32_t prim;
    } *closest = malloc(8 * (size_t)n + 1);
    for (int run = -1; run < runs; run++) {
      double start = seconds(CLOCK_THREAD_CPUTIME_ID), wall = seconds(CLOCK_MONOTONIC);
      for (uint32_t i = 0; i < n; i++) {
        const Ray *r = &rays[i];
        struct RTCRayHit rh;
        rh.ray.org_x = r->o[0], rh.ray.org_y = r->o[1], rh.ray.org_z = r->o[2];
        rh.ray.dir_x = r->d[0], rh.ray.dir_y = r->d[1], rh.ray.dir_z = r->d[2];
        rh.ray.tnear = r->tnear, rh.ray.tfar = r->tfar, rh.ray.time = 0;
        rh.ray.mask = -1, rh.ray.id = 0, rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
          closest[i].t = INFINITY, closest[i].prim = UINT32_MAX;
        } else {
          closest[i].t = rh.ray.tfar;
          closest[i].prim = rh.hit.geomID == MESH ? g.triangle_prim[rh.hit.primID]
                                                  : g.sphere_prim[rh.hit.primID];
        }
      }
      if (run >= 0) {
        times[run] = seconds(CLOCK_THREAD_CPUTIME_ID) - start;
        walls[run] = seconds(CLOCK_MONOTONIC) - wall;
      }
    }
    uint32_t hits = 0;
    double checksum = 0;
    for (uint32_t i = 0; i < n; i++)
      if (closest[i].prim != UINT32_MAX)
        hits++, checksum += closest[i].t;
    double m = median(times, runs);
    ROW("trace\t%s\tclosest\t%u\t%u\t%.17g\t%.9f\t%.9f\t%.9f\t%.9f\n", sets[s], n, hits, checksum,
        m, times[0], times[runs - 1], median(walls, runs));
    fprintf(stderr, "%s %s: Embree %s %.2f Mrays/s closest, %u hits, checksum %.6f\n", dir,
            sets[s], quality_name, n / m / 1e6, hits, checksum);
    snprintf(path, sizeof path, "%s/%s.embree-%s.closest", dir, sets[s], quality_name);
    spit(path, closest, 8 * (size_t)n);
    free(closest);

    /* Any hit: 1 when occluded (Embree sets tfar to -inf). */
    unsigned char *any = malloc((size_t)n + 1);
    for (int run = -1; run < runs; run++) {
      double start = seconds(CLOCK_THREAD_CPUTIME_ID), wall = seconds(CLOCK_MONOTONIC);
      for (uint32_t i = 0; i < n; i++) {
        const Ray *r = &rays[i];
        struct RTCRay ray;
        ray.org_x = r->o[0], ray.org_y = r->o[1], ray.org_z = r->o[2];
        ray.dir_x = r->d[0], ray.dir_y = r->d[1], ray.dir_z = r->d[2];
        ray.tnear = r->tnear, ray.tfar = r->tfar, ray.time = 0;
        ray.mask = -1, ray.id = 0, ray.flags = 0;
        rtcOccluded1(scene, &context, &ray);
        any[i] = ray.tfar == -INFINITY;
      }
      if (run >= 0) {
        times[run] = seconds(CLOCK_THREAD_CPUTIME_ID) - start;
        walls[run] = seconds(CLOCK_MONOTONIC) - wall;
      }
    }
    hits = 0;
    for (uint32_t i = 0; i < n; i++)
      hits += any[i];
    m = median(times, runs);
    ROW("trace\t%s\tany\t%u\t%u\t0\t%.9f\t%.9f\t%.9f\t%.9f\n", sets[s], n, hits, m, times[0],
        times[runs - 1], median(walls, runs));
    snprintf(path, sizeof path, "%s/%s.embree-%s.any", dir, sets[s], quality_name);
    spit(path, any, n);
    free(any);
    free(rays);
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  snprintf(path, sizeof path, "%s/embree-%s.tsv", dir, quality_name);
  spit(path, rows, used);
  return 0;
}
