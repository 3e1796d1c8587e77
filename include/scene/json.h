/* json.h: a small JSON (RFC 8259) reader for glTF: the text becomes a tree of values.
 *
 * Owns: the tree (one arena per document: json_free releases it all). Strings are decoded
 * (escapes, \u surrogate pairs to UTF-8) and NUL-terminated; a string holding a NUL keeps
 * its length in n. Numbers are doubles (strtod on the number's own bytes: rastty never sets
 * a locale). Every value remembers its byte offset in the text, so a loader can say where
 * a bad value is ("m.gltf: byte 812: accessor 3: count must be at least 1").
 *
 * Limits: nesting JSON_MAX_DEPTH (a recursive descent; a deeper file is an error, never a
 * stack overflow, even under `ulimit -s 64`), JSON_MAX_VALUES values in all. Errors name the
 * byte offset and what was expected ("byte 57: expected ',' or '}' after an object member,
 * got 'x'"); bytes from the file are quoted printable (err_quote), never raw. Duplicate
 * object keys: the last wins (json_get), as most readers do. */
#ifndef RASTTY_JSON_H
#define RASTTY_JSON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "err.h"

#define JSON_MAX_DEPTH 64
#define JSON_MAX_VALUES (64u << 20)

enum json_type { JSON_NULL, JSON_BOOL, JSON_NUMBER, JSON_STRING, JSON_ARRAY, JSON_OBJECT };

struct json {
    enum json_type type;
    uint32_t n;              /* array, object: members; string: bytes */
    size_t at;               /* byte offset of the value's first byte in the text */
    double num;              /* number; bool: 0 or 1 */
    const char *str;         /* string (decoded, NUL-terminated) */
    const struct json *kids; /* array, object: the n members in order */
    const char *const *keys; /* object: their n keys */
};

struct json_arena;

struct json_doc {
    const struct json *root;
    struct json_arena *arena;
};

/* Parse text[0..len) (an optional UTF-8 byte-order mark, then one value and blanks). On
 * error: -1, e = "byte N: problem" (the caller puts the file name in front). */
int json_parse(const char *text, size_t len, struct json_doc *doc, struct err *e);
void json_free(struct json_doc *doc);

/* Member `key` of an object (the last of that name), or NULL (also when v is not an object). */
const struct json *json_get(const struct json *v, const char *key);
/* Element i of an array, or NULL. */
const struct json *json_at(const struct json *v, uint32_t i);
/* The value as a number / whole number / string / bool when it is one (else the default):
 * json_int takes only whole numbers within [INT64_MIN/2, INT64_MAX/2]. */
double json_num(const struct json *v, double dflt);
bool json_is_int(const struct json *v);
int64_t json_int(const struct json *v, int64_t dflt);
const char *json_str(const struct json *v, const char *dflt);
bool json_bool(const struct json *v, bool dflt);
/* v's members when it is an array (0 when it is anything else). */
uint32_t json_len(const struct json *v);

#endif
