#include "engine/core/buffer.h"

namespace masav {

const char* elem_kind_name(ElemKind kind) {
  switch (kind) {
    case ElemKind::u32: return "u32";
    case ElemKind::i32: return "i32";
    case ElemKind::f32: return "f32";
    case ElemKind::real: return "real";
    case ElemKind::real4: return "real4";
  }
  return "?";
}

size_t elem_bytes(ElemKind kind, size_t real_bytes) {
  switch (kind) {
    case ElemKind::u32:
    case ElemKind::i32:
    case ElemKind::f32: return 4;
    case ElemKind::real: return real_bytes;
    case ElemKind::real4: return 4 * real_bytes;
  }
  return 0;
}

}  // namespace masav
