#!/usr/bin/env python3
"""Issue 53 experiment: a SPIR-V module rewritten from the Vulkan memory model (what rust-gpu
declares) to GLSL450 (what glslang declares), with nothing else changed: the VulkanMemoryModel
capabilities and the SPV_KHR_vulkan_memory_model extension dropped, OpMemoryModel's model set to
GLSL450. Valid for modules that use none of the Vulkan model's memory operands (checked: any
MakePointer*/NonPrivate operand would make spirv-val refuse the result).
    python3 glsl450.py IN.spv OUT.spv"""
import struct
import sys

VULKAN_MM_CAPS = {5345, 5346, 5347}  # VulkanMemoryModel, ...DeviceScope, ...AvailabilityVisibilityChains


def rewrite(words):
    out = words[:5]
    i = 5
    while i < len(words):
        count, op = words[i] >> 16, words[i] & 0xFFFF
        inst = words[i:i + count]
        i += count
        if op == 17 and inst[1] in VULKAN_MM_CAPS:  # OpCapability
            continue
        if op == 10:  # OpExtension
            name = struct.pack("<%dI" % (count - 1), *inst[1:]).split(b"\0")[0]
            if name == b"SPV_KHR_vulkan_memory_model":
                continue
        if op == 14:  # OpMemoryModel: addressing, model (GLSL450 = 1)
            inst = [inst[0], inst[1], 1]
        out += inst
    return out


def main():
    data = open(sys.argv[1], "rb").read()
    words = list(struct.unpack("<%dI" % (len(data) // 4), data))
    out = rewrite(words)
    open(sys.argv[2], "wb").write(struct.pack("<%dI" % len(out), *out))


main()
