#pragma once
// The vocabulary file: the one reader and writer of depot's binary
// vocabulary format.
//
// Layout (little-endian): "DEPOTVOC"; u32 format version (1); u32
// descriptor bytes (32); u32 branching; u32 levels; u32 node count; per node
// in breadth-first order u32 parent, u32 depth, i32 word (-1 inner), f32 idf,
// 32 descriptor bytes; u32 CRC-32 of everything before it. The CRC is also
// the vocabulary's identity (maps record which vocabulary made them).
#include <cstdint>
#include <memory>
#include <string>

#include "slam/place/vocabulary.h"

namespace depot::slam {

// Writes through a staged file: a failed write leaves nothing.
void save_vocabulary(const Vocabulary& vocabulary, const std::string& path);

// Throws depot::Error "<path>: <problem>" for a missing, truncated or
// corrupt file (checksum), another format or version, or descriptors of
// another size than 32 bytes.
Vocabulary load_vocabulary(const std::string& path);

// As load_vocabulary, shared: a file already loaded by this process (same
// path, size and modification time) is not read again.
std::shared_ptr<const Vocabulary> load_vocabulary_shared(const std::string& path);

// CRC-32 of the vocabulary's file bytes.
uint32_t vocabulary_identity(const Vocabulary& vocabulary);

// An identity as every message shows it: eight hex digits ("0a1b2c3d").
std::string format_vocabulary_identity(uint32_t identity);

// $DEPOT_VOCABULARY when set, otherwise the vocabulary the build trained
// (build/vocabulary/depot_orb.voc).
std::string default_vocabulary_path();

}  // namespace depot::slam
