// The Vulkan backend's binding table (compute/vk_bindings.h, generated from kernels.inc) against
// the shaders it binds: for every kernel whose shader carries its name, each resource the shader
// declares sits in descriptor set 0 at a binding the table lists, of the kind the table says
// (storage buffer, or uniform texel buffer of float or uint texels), and binding 0 is the
// diagnostics word; every specialisation id a shader reads is one of shaders/spec_ids.h. No device
// is needed: the SPIR-V words are parsed here.
#include <doctest/doctest.h>

#include <cstdint>
#include <map>
#include <set>
#include <span>
#include <string>

#include "compute/vk_backend.h"
#include "compute/vk_bindings.h"
#include "shaders/embedded.h"
#include "shaders/spec_ids.h"

namespace {

using masav::KernelId;
using masav::vk::BindingKind;

enum class Declared { storage, texel_float, texel_uint, other };

struct ShaderResources {
  std::map<uint32_t, Declared> bindings;  // set 0, by binding
  std::set<uint32_t> other_sets;          // any set but 0 (none expected)
  std::set<uint32_t> spec_ids;
  bool well_formed = true;
};

// SPIR-V opcodes, storage classes and decorations this reader needs (SPIR-V 1.3 specification).
constexpr uint32_t kMagic = 0x07230203;
constexpr uint32_t kOpTypeInt = 21, kOpTypeFloat = 22, kOpTypeImage = 25, kOpTypeSampledImage = 27,
                   kOpTypePointer = 32, kOpVariable = 59, kOpDecorate = 71;
constexpr uint32_t kDecorationSpecId = 1, kDecorationBlock = 2, kDecorationBufferBlock = 3,
                   kDecorationBinding = 33, kDecorationDescriptorSet = 34;
constexpr uint32_t kStorageUniformConstant = 0, kStorageUniform = 2, kStorageStorageBuffer = 12;
constexpr uint32_t kDimBuffer = 5;

ShaderResources read_resources(std::span<const uint32_t> words) {
  ShaderResources r;
  if (words.size() < 5 || words[0] != kMagic) {
    r.well_formed = false;
    return r;
  }
  std::map<uint32_t, uint32_t> binding, set, pointee, pointer_class;
  std::set<uint32_t> buffer_blocks, float_types, uint_types;
  std::map<uint32_t, uint32_t> texel_image_of;  // image type id -> sampled type id (Dim Buffer)
  std::map<uint32_t, uint32_t> image_sampled;   // image type id -> its Sampled operand
  std::map<uint32_t, uint32_t> sampled_image_of;  // (u)samplerBuffer type id -> its image type
  std::map<uint32_t, uint32_t> variables;       // variable id -> pointer type id
  std::map<uint32_t, uint32_t> variable_class;  // variable id -> storage class
  for (size_t at = 5; at < words.size();) {
    const uint32_t count = words[at] >> 16, op = words[at] & 0xffffu;
    if (count == 0 || at + count > words.size()) {
      r.well_formed = false;
      return r;
    }
    const uint32_t* w = &words[at];
    if (op == kOpDecorate && count >= 3) {
      if (w[2] == kDecorationBinding && count >= 4) binding[w[1]] = w[3];
      if (w[2] == kDecorationDescriptorSet && count >= 4) set[w[1]] = w[3];
      if (w[2] == kDecorationSpecId && count >= 4) r.spec_ids.insert(w[3]);
      if (w[2] == kDecorationBufferBlock) buffer_blocks.insert(w[1]);
      if (w[2] == kDecorationBlock) buffer_blocks.insert(w[1]);
    } else if (op == kOpTypeFloat && count >= 2) {
      float_types.insert(w[1]);
    } else if (op == kOpTypeInt && count >= 4 && w[3] == 0) {
      uint_types.insert(w[1]);
    } else if (op == kOpTypeImage && count >= 9) {
      if (w[3] == kDimBuffer) texel_image_of[w[1]] = w[2];
      image_sampled[w[1]] = w[7];
    } else if (op == kOpTypeSampledImage && count >= 3) {
      sampled_image_of[w[1]] = w[2];
    } else if (op == kOpTypePointer && count >= 4) {
      pointer_class[w[1]] = w[2];
      pointee[w[1]] = w[3];
    } else if (op == kOpVariable && count >= 4) {
      variables[w[2]] = w[1];
      variable_class[w[2]] = w[3];
    }
    at += count;
  }
  for (const auto& [var, ptr] : variables) {
    const auto b = binding.find(var);
    if (b == binding.end()) continue;  // not a descriptor
    const uint32_t s = set.count(var) ? set[var] : 0;
    if (s != 0) {
      r.other_sets.insert(s);
      continue;
    }
    const uint32_t cls = variable_class[var];
    uint32_t type = pointee[ptr];
    if (sampled_image_of.count(type)) type = sampled_image_of[type];
    Declared kind = Declared::other;
    if (cls == kStorageStorageBuffer || (cls == kStorageUniform && buffer_blocks.count(type)))
      kind = Declared::storage;
    else if (cls == kStorageUniformConstant && texel_image_of.count(type) &&
             image_sampled[type] == 1) {
      const uint32_t sampled = texel_image_of[type];
      kind = float_types.count(sampled)  ? Declared::texel_float
             : uint_types.count(sampled) ? Declared::texel_uint
                                         : Declared::other;
    }
    if (r.bindings.count(b->second)) r.well_formed = false;  // two resources at one binding
    r.bindings[b->second] = kind;
  }
  return r;
}

const char* name_of(Declared d) {
  switch (d) {
    case Declared::storage: return "storage buffer";
    case Declared::texel_float: return "float texel buffer";
    case Declared::texel_uint: return "uint texel buffer";
    default: return "something else";
  }
}

// What the table says binding `b` of kernel `k` is, as the shader would declare it.
Declared expected(const masav::vk::Texels& t, BindingKind kind) {
  if (kind == BindingKind::storage) return Declared::storage;
  if (t.format == ::vk::Format::eR32Uint || t.format == ::vk::Format::eR32G32B32A32Uint)
    return Declared::texel_uint;
  return Declared::texel_float;
}

}  // namespace

TEST_CASE("vulkan binding table matches every kernel shader's declared bindings") {
  size_t checked = 0;
  for (const KernelId k : masav::kAllKernels) {
    const std::string name(masav::kernel_name(k));
    const std::span<const uint32_t> spirv = masav::shaders::find(name);
    // A kernel run as several dispatches, or with a shader chosen per call, binds its own way.
    if (masav::vk::runs_own(k) || spirv.empty()) continue;
    CAPTURE(name);
    const ShaderResources r = read_resources(spirv);
    REQUIRE(r.well_formed);
    CHECK(r.other_sets.empty());
    // Binding 0: the diagnostics word (shaders/common/kernel_base.glsl).
    REQUIRE(r.bindings.count(0));
    CHECK(r.bindings.at(0) == Declared::storage);
    const auto table = masav::vk::kernel_bindings(k);
    const auto extra = masav::vk::kernel_extra(k);
    for (const auto& [binding, declared] : r.bindings) {
      if (binding == 0) continue;
      CAPTURE(binding);
      const std::string declared_as = name_of(declared);
      CAPTURE(declared_as);
      const size_t index = binding - 1;
      if (index < table.size()) {
        const auto& entry = table[index];
        // An any_in texel buffer's format is chosen per call: float or uint both fit.
        if (entry.kind == BindingKind::texel && entry.texels.format == ::vk::Format::eUndefined)
          CHECK((declared == Declared::texel_float || declared == Declared::texel_uint));
        else
          CHECK(declared == expected(entry.texels, entry.kind));
      } else {
        // Only the one binding after the buffers (kernel_extra) may follow them.
        REQUIRE_MESSAGE(index == table.size(), "binding beyond the kernel's buffers");
        REQUIRE_MESSAGE(extra.has_value(), "binding after the buffers, but no kernel_extra");
        const BindingKind kind = extra->format == ::vk::Format::eUndefined ? BindingKind::storage
                                                                          : BindingKind::texel;
        CHECK(declared == expected(*extra, kind));
      }
    }
    // The table's extra binding is one the shader declares.
    if (extra) CHECK(r.bindings.count(uint32_t(table.size() + 1)));
    // Every specialisation id is one of spec_ids.h.
    for (const uint32_t id : r.spec_ids) {
      CAPTURE(id);
      CHECK(id < std::size(masav::kSpecIds));
    }
    ++checked;
  }
  // Every kernel but the few run their own way is one dispatch of its own shader.
  size_t own = 0;
  for (const KernelId k : masav::kAllKernels) own += masav::vk::runs_own(k);
  CHECK(checked == masav::kKernelCount - own);
}

TEST_CASE("spirv reader refuses words that are not a module") {
  const uint32_t not_spirv[] = {1, 2, 3, 4, 5, 6};
  CHECK_FALSE(read_resources(not_spirv).well_formed);
  // A header and an instruction whose word count runs past the end.
  const uint32_t truncated[] = {kMagic, 0x10300, 0, 10, 0, (7u << 16) | kOpDecorate, 1};
  CHECK_FALSE(read_resources(truncated).well_formed);
}
