/*
 * ellicast.h: the C API of ellicast (C99; no C++ type crosses it).
 *
 * ellicast sends 3D models over lossy one-way channels (broadcast, multicast, radio, satellite) as
 * small self-contained packets (spec/format.md). This header is what an integrator embeds: a viewer,
 * a set-top box or a game engine that receives a stream, or a sender that makes one.
 *
 *   Receiving:  ellicast_receiver_create, then ellicast_receiver_take_datagram for every UDP datagram
 *               (or ellicast_receiver_take_file / _take_recording for a recorded .ellc stream), then at
 *               any moment ellicast_receiver_progress (how much has arrived) and
 *               ellicast_receiver_snapshot (the model as it can be shown now: GLB bytes, or meshes as
 *               arrays). A receiver may tune in at any time; loss, duplication and reordering only
 *               lower the quality of a snapshot until the missing packets come round again.
 *   Sending:    ellicast_encode_file / ellicast_encode_memory turn a glTF/GLB, OBJ, PLY, OFF or STL
 *               model into a recorded stream (.ellc bytes); ellicast_recording_next_packet walks its
 *               packets, each one datagram to send.
 *
 * Errors: every call that can fail returns an ellicast_status; ELLICAST_OK (0) is success. On failure,
 * ellicast_last_error() gives a message naming what was wrong (the file, the option, the packet),
 * valid on the calling thread until its next call into this library. No call aborts, throws or
 * prints: a corrupt file or a hostile datagram is an error code and a message.
 *
 * Memory: objects made by a _create / _snapshot call are freed by the matching _destroy; buffers the
 * library fills (ellicast_buffer) are freed with ellicast_buffer_free. Pointers returned inside a
 * snapshot (mesh arrays, names) stay valid until that snapshot is destroyed.
 *
 * Threads: calls on different objects may run on different threads at once; calls on one object
 * must not overlap.
 *
 * Link: pkg-config --cflags --libs ellicast, or find_package(ellicast CONFIG) and the target
 * ellicast::ellicast (shared library libellicast.so, SONAME libellicast.so.1).
 */
#ifndef ELLICAST_H
#define ELLICAST_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#define ELLICAST_API
#elif defined(__GNUC__)
#define ELLICAST_API __attribute__((visibility("default")))
#else
#define ELLICAST_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* The library's version (1.0.0: the SONAME's major is 1) and the newest format version it reads and
 * writes (spec/format.md: 1.14). */
#define ELLICAST_VERSION_MAJOR 1
#define ELLICAST_VERSION_MINOR 0
#define ELLICAST_VERSION_PATCH 0

typedef enum ellicast_status {
    ELLICAST_OK = 0,
    ELLICAST_ERROR_ARGUMENT = 1, /* a NULL pointer where one is needed, an option out of range */
    ELLICAST_ERROR_IO = 2,       /* a file that cannot be read or written */
    ELLICAST_ERROR_INPUT = 3,    /* a model or recording that cannot be used: corrupt, truncated, unsupported */
    ELLICAST_ERROR_REJECTED = 4, /* a datagram dropped: not ellicast, damaged, another stream, malformed;
                                    the receiver counts it and goes on (this is not fatal) */
    ELLICAST_ERROR_NOT_READY = 5, /* nothing can be shown yet (no stream info, or no object has arrived) */
    ELLICAST_ERROR_MEMORY = 6,   /* out of memory, or a limit of the receiver reached */
    ELLICAST_ERROR_INTERNAL = 7  /* a bug: please report it with the message */
} ellicast_status;

/* "1.0.0". */
ELLICAST_API const char* ellicast_version(void);
/* The newest format version this library reads and writes (major 1, minor 14). */
ELLICAST_API void ellicast_format_version(int* major, int* minor);
/* A short name for a status ("ELLICAST_ERROR_INPUT", ...). */
ELLICAST_API const char* ellicast_status_name(ellicast_status status);
/* The message of the last call on this thread that failed ("" after a call that succeeded). Never NULL. */
ELLICAST_API const char* ellicast_last_error(void);

/* Bytes the library allocated for the caller; free with ellicast_buffer_free. */
typedef struct ellicast_buffer {
    uint8_t* data;
    size_t size;
} ellicast_buffer;
/* Frees the bytes and sets data to NULL and size to 0. NULL or an empty buffer is fine. */
ELLICAST_API void ellicast_buffer_free(ellicast_buffer* buffer);

/* ------------------------------------------------------------------------------------------------
 * Receiving
 */

typedef struct ellicast_receiver ellicast_receiver;

typedef struct ellicast_receiver_options {
    size_t struct_size;        /* sizeof(ellicast_receiver_options): set by _init, keeps the ABI growable */
    int has_stream_id;         /* nonzero: keep only the packets of stream_id */
    uint32_t stream_id;
    const char* public_key_path; /* NULL: any sender; else a public key file from `ellicast keygen`
                                    (NAME.pub): only packets that sender signed are taken (spec 16) */
    int grid_resolution;       /* cells of the decoder's inside/outside grid along an object's frame; 0:
                                  automatic (the stream's hint, bounded by what arrived), else 4..1024 */
    int exact;                 /* nonzero (default): an object whose every point and exact layer arrived is
                                  shown as its original triangles */
    uint64_t max_pending_bytes; /* memory for packets held before their stream info; 0: the default, 64 MiB */
} ellicast_receiver_options;

/* Fills `options` with the defaults. */
ELLICAST_API void ellicast_receiver_options_init(ellicast_receiver_options* options);

/* A receiver that has taken nothing yet. `options` may be NULL (the defaults). */
ELLICAST_API ellicast_status ellicast_receiver_create(const ellicast_receiver_options* options, ellicast_receiver** out);
ELLICAST_API void ellicast_receiver_destroy(ellicast_receiver* receiver);

/* Takes one datagram as it came off the network (one packet). ELLICAST_OK when it was taken, new or a
 * repeat; ELLICAST_ERROR_REJECTED (with the reason in ellicast_last_error) when it was dropped, which
 * a receiver just counts: someone else's traffic, a damaged packet or a forged one. */
ELLICAST_API ellicast_status ellicast_receiver_take_datagram(ellicast_receiver* receiver, const void* data, size_t size);

/* Takes every intact packet of a recorded stream (.ellc container bytes, or a file), as if each had
 * arrived as a datagram; damaged regions are skipped. ELLICAST_ERROR_INPUT when the bytes are not a
 * container at all (with the reason); a recording with damage or loss is taken, not refused. */
ELLICAST_API ellicast_status ellicast_receiver_take_recording(ellicast_receiver* receiver, const void* data, size_t size);
ELLICAST_API ellicast_status ellicast_receiver_take_file(ellicast_receiver* receiver, const char* path);

typedef struct ellicast_progress {
    uint64_t datagrams;        /* every datagram or packet given */
    uint64_t accepted;         /* brought new content */
    uint64_t duplicates;       /* valid, nothing new (a carousel repeats its base) */
    uint64_t rejected;         /* dropped: not ellicast, damaged, another stream, invalid, unsigned */
    double loss;               /* loss estimated from the sender's sequence numbers, 0..1 */
    uint32_t objects;          /* objects the stream declares (0 before its stream info) */
    uint64_t points_received;  /* surface points held, over all objects */
    uint64_t points_declared;
    uint64_t ellipsoids_received;
    uint64_t ellipsoids_declared;
    uint32_t exact_objects;    /* objects whose every point and exact layer have arrived */
    int base_complete;         /* nonzero: every object's base has arrived (a first picture can be shown) */
    int complete;              /* nonzero: everything the stream declares has arrived */
} ellicast_progress;

ELLICAST_API ellicast_status ellicast_receiver_progress(const ellicast_receiver* receiver, ellicast_progress* out);

typedef struct ellicast_object_progress {
    int arrived;               /* its stream info entry has arrived */
    int point_set;             /* a point cloud (no surface) */
    uint64_t points_received, points_declared;
    uint64_t ellipsoids_received, ellipsoids_declared;
    int has_exact_layer;       /* the stream carries its original triangles */
    int exact;                 /* every point and the exact layer have arrived */
} ellicast_object_progress;

/* Progress of object `index` < ellicast_progress.objects. */
ELLICAST_API ellicast_status ellicast_receiver_object_progress(const ellicast_receiver* receiver, uint32_t index,
                                                              ellicast_object_progress* out);

/* ------------------------------------------------------------------------------------------------
 * Snapshots: the model as a receiver can show it now
 */

typedef struct ellicast_snapshot ellicast_snapshot;

/* Decodes what has arrived (the ellipsoids' base, every point inserted, the exact layer where whole)
 * into a snapshot. ELLICAST_ERROR_NOT_READY while nothing can be built yet. Later takes do not change
 * a snapshot already made. Decoding a large model takes time in proportion to its points. */
ELLICAST_API ellicast_status ellicast_receiver_snapshot(ellicast_receiver* receiver, ellicast_snapshot** out);
ELLICAST_API void ellicast_snapshot_destroy(ellicast_snapshot* snapshot);

/* The snapshot as a GLB file (glTF 2.0, binary): the scene, materials, textures, animations and skins
 * that arrived, valid for the Khronos glTF-Validator. */
ELLICAST_API ellicast_status ellicast_snapshot_glb(const ellicast_snapshot* snapshot, ellicast_buffer* out);

/* The snapshot as plain meshes in world space (node transforms applied), one per object and node
 * that shows it. */
ELLICAST_API size_t ellicast_snapshot_mesh_count(const ellicast_snapshot* snapshot);

typedef struct ellicast_mesh {
    const char* name;
    size_t vertex_count;
    const float* positions;    /* 3 floats a vertex */
    const float* normals;      /* 3 floats a vertex, or NULL */
    const float* texcoords;    /* 2 floats a vertex, or NULL */
    const float* colors;       /* 4 floats a vertex (linear RGBA in [0, 1]), or NULL */
    int color_has_alpha;       /* the model's colours were RGBA (else alpha is 1) */
    size_t triangle_count;     /* 0: a point set */
    const uint32_t* indices;   /* 3 vertex indices a triangle, counter-clockwise seen from outside */
} ellicast_mesh;

/* Mesh `index` < ellicast_snapshot_mesh_count; its arrays belong to the snapshot. */
ELLICAST_API ellicast_status ellicast_snapshot_mesh(const ellicast_snapshot* snapshot, size_t index, ellicast_mesh* out);

/* Shorthand: snapshot, GLB bytes, destroy. */
ELLICAST_API ellicast_status ellicast_receiver_snapshot_glb(ellicast_receiver* receiver, ellicast_buffer* out);

/* ------------------------------------------------------------------------------------------------
 * Sending
 */

typedef struct ellicast_encode_options {
    size_t struct_size;        /* sizeof(ellicast_encode_options): set by _init; older, smaller structs are accepted */
    uint32_t stream_id;        /* written in every packet (default 1) */
    uint32_t packet_size;      /* largest packet in bytes, 128..65000 (default 1200: one datagram under the IPv6 minimum MTU) */
    int position_bits;         /* 8..16 (default 14) */
    uint32_t max_ellipsoids;   /* per object, 1..100000 (default 400) */
    double repair_ratio;       /* repair packets per point packet, 0..4 (default 1) */
    double sample_spacing;     /* surface samples on large triangles, as a share of the diagonal, 0..1 (default 0.03; 0: none) */
    int point_map;             /* nonzero (default): mapped points (format 1.7) where they take fewer bytes */
    double normal_tolerance;   /* degrees, 0..90 (default 2): normals this close to the surface's are left out (format 1.8) */
    unsigned threads;          /* worker threads (default 2; the output does not depend on it) */
    int allow_external_paths;  /* nonzero: a glTF may name files outside its folder */
    /* Called with a stage name and the share done (0..1) while encoding; may be NULL. */
    void (*progress)(const char* stage, double fraction, void* user);
    void* progress_user;
    /* Added in 1.1 (a caller built against 1.0 passes the smaller struct_size and gets the default):
     * surface samples per original vertex of an object at most, -1..1000 (default 0.25; -1: no limit
     * but the spacing's). */
    double sample_budget;
    /* Added in 1.1 too: an object's ellipsoids take at most this multiple of the bytes of its points
     * and triangles (at least 8), 0..1000 (default 1; 0: max_ellipsoids alone). */
    double base_ratio;
} ellicast_encode_options;

/* Fills `options` with the defaults (those of `ellicast encode`). */
ELLICAST_API void ellicast_encode_options_init(ellicast_encode_options* options);

/* Encodes a model file (glTF/GLB with its scene, OBJ, PLY, OFF or STL) into a recorded stream: the
 * bytes of an .ellc container, every packet in transmission order. `options` may be NULL. */
ELLICAST_API ellicast_status ellicast_encode_file(const char* model_path, const ellicast_encode_options* options,
                                                  ellicast_buffer* stream_out);

/* The same for a model held in memory; `type` names its format: "glb", "gltf" (only a glTF whose
 * buffers and images are embedded as data: URIs), "obj", "ply", "off" or "stl". */
ELLICAST_API ellicast_status ellicast_encode_memory(const void* data, size_t size, const char* type,
                                                    const ellicast_encode_options* options, ellicast_buffer* stream_out);

/* Walks the packets of a recorded stream: start with *offset = 0; each call sets *packet and
 * *packet_size to the next intact packet (one datagram to send) and advances *offset. Returns
 * ELLICAST_OK with *packet NULL at the end; damaged bytes are skipped (the next intact packet is
 * found); ELLICAST_ERROR_INPUT when the bytes are not a container. *packet points into `data`. */
ELLICAST_API ellicast_status ellicast_recording_next_packet(const void* data, size_t size, size_t* offset,
                                                            const uint8_t** packet, size_t* packet_size);

#ifdef __cplusplus
}
#endif

#endif /* ELLICAST_H */
