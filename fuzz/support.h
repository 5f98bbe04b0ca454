// What every fuzz target shares: the input bytes as a file, and the one outcome bad input may have (InputError).
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

namespace vr::fuzz {

// A folder of this process's own, in $VR_FUZZ_SCRATCH (scripts/fuzz.sh sets it and removes it afterwards: libFuzzer
// leaves without exit handlers), else in /dev/shm where there is one (no disk traffic per execution).
const std::filesystem::path& scratchDir();

// Writes the bytes to scratchDir() / name and returns that path.
std::filesystem::path writeInput(const std::string& name, std::string_view bytes);

// The input's first line names the file (made safe, and given the first of `suffixes` unless it ends in one of
// them); the rest is its content. Lets the fuzzer vary names that carry information (raw dims and type).
struct NamedInput {
    std::string name;
    std::string_view bytes;
};
NamedInput splitNamedInput(const uint8_t* data, std::size_t size, std::initializer_list<std::string_view> suffixes);

// loadVolume() on path: InputError is fine; any other exception escapes (libFuzzer reports it), and a volume that
// breaks Volume's invariants (dims, spacing, one finite value per voxel) aborts. With VR_FUZZ_VERBOSE set it prints
// each outcome (to check that the seeds reach the loaders' success paths).
void loadExpectingInputError(const std::filesystem::path& path);

// Aborts with a message: a finding that is not a crash by itself.
[[noreturn]] void finding(const std::string& what);

}  // namespace vr::fuzz
