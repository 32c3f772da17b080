//! Liveness on small modules whose answer is known: assembled here by `spirv-as` (a straight
//! line, a loop with phis, a call into a function that traces, variables written whole and in
//! part), and a glslang stage compiled with debug lines.

use super::*;
use std::process::Command;

/// The module `body` (functions) after a header declaring what every test uses.
fn assemble(body: &str) -> Vec<u8> {
    let text = format!("{HEADER}{body}");
    let hash = text.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3));
    let dir = std::env::temp_dir().join(format!("twinray-inspect-{}-{hash:x}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (src, out) = (dir.join("m.spvasm"), dir.join("m.spv"));
    std::fs::write(&src, text).unwrap();
    let run = Command::new("spirv-as")
        .args(["--target-env", "spv1.4", "-o"])
        .arg(&out)
        .arg(&src)
        .output()
        .expect("spirv-as runs (cargo xtask setup installs spirv-tools)");
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let bytes = std::fs::read(&out).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    bytes
}

const HEADER: &str = r#"
               OpCapability Shader
               OpCapability RayTracingKHR
               OpExtension "SPV_KHR_ray_tracing"
               OpMemoryModel Logical GLSL450
               OpEntryPoint RayGenerationKHR %main "main" %tlas %payload %seedvar
               OpName %main "main"
               OpName %shade "shade"
               OpName %kept "kept"
               OpDecorate %tlas DescriptorSet 0
               OpDecorate %tlas Binding 0
       %void = OpTypeVoid
         %fn = OpTypeFunction %void
      %float = OpTypeFloat 32
       %uint = OpTypeInt 32 0
       %bool = OpTypeBool
    %v2float = OpTypeVector %float 2
    %v3float = OpTypeVector %float 3
 %ptr_float = OpTypePointer Function %float
  %ptr_vec2 = OpTypePointer Function %v2float
   %fn_shade = OpTypeFunction %float %ptr_float
         %as = OpTypeAccelerationStructureKHR
     %ptr_as = OpTypePointer UniformConstant %as
       %tlas = OpVariable %ptr_as UniformConstant
%ptr_payload = OpTypePointer RayPayloadKHR %v3float
    %payload = OpVariable %ptr_payload RayPayloadKHR
%ptr_private = OpTypePointer Private %float
    %seedvar = OpVariable %ptr_private Private
         %f0 = OpConstant %float 0
         %f1 = OpConstant %float 1
         %u0 = OpConstant %uint 0
         %u1 = OpConstant %uint 1
         %u4 = OpConstant %uint 4
      %false = OpConstantFalse %bool
     %origin = OpConstantComposite %v3float %f1 %f1 %f1
      %zero3 = OpConstantComposite %v3float %f0 %f0 %f0
"#;

/// A trace of the ray along `dir`.
fn trace(dir: &str) -> String {
    format!("%t_{dir} = OpLoad %as %tlas\nOpTraceRayKHR %t_{dir} %u0 %u1 %u0 %u0 %u0 %origin %f0 %{dir} %f1 %payload\n")
}

fn sites(body: &str) -> Vec<Site> {
    let entries = inspect(&assemble(body)).unwrap();
    assert_eq!(entries.len(), 1);
    assert_eq!(entries[0].model, "RayGenerationKHR");
    entries[0].sites.clone()
}

fn live_ids(site: &Site) -> Vec<String> {
    let mut ids: Vec<String> = site.live.iter().map(|l| format!("{}:{}", l.made_by, l.bytes)).collect();
    ids.sort();
    ids
}

#[test]
fn only_what_is_used_after_the_call_is_live_across_it() {
    let body = format!(
        "%main = OpFunction %void None %fn\n%entry = OpLabel\n\
         %seed = OpLoad %float %seedvar\n%after = OpFAdd %float %seed %f1\n\
         %before = OpFMul %float %seed %f1\n\
         %dir = OpCompositeConstruct %v3float %before %before %before\n\
         %unused = OpFSub %float %before %f1\n%folded = OpFMul %float %f1 %f1\n\
         {}\
         %p = OpLoad %v3float %payload\n%s0 = OpVectorTimesScalar %v3float %p %after\n\
         %s = OpVectorTimesScalar %v3float %s0 %folded\nOpStore %payload %s\n\
         OpReturn\nOpFunctionEnd\n",
        trace("dir")
    );
    let sites = sites(&body);
    assert_eq!(sites.len(), 1);
    assert_eq!(sites[0].call, "OpTraceRayKHR");
    // %after alone: not %before, the direction or the handle (used by the trace itself), nor
    // %unused, nor %folded (made of constants alone: a driver folds it).
    assert_eq!(live_ids(&sites[0]), ["OpFAdd:4"]);
    assert_eq!(sites[0].bytes, 4);
    assert!(sites[0].loops.is_empty());
}

/// A counted loop around a trace, summing the payload; `%init` feeds the counter's phi from
/// the entry, `%exit_only` a phi of the exit block from the header, `%k` is used after the loop.
const LOOP: &str = "%main = OpFunction %void None %fn\n%entry = OpLabel\n\
    %init = OpIAdd %uint %u0 %u0\n%seed = OpLoad %float %seedvar\n%k = OpFAdd %float %seed %f1\n\
    %exit_only = OpFMul %float %seed %f1\n%dir = OpCompositeConstruct %v3float %seed %f0 %f0\nOpBranch %header\n\
    %header = OpLabel\n%i = OpPhi %uint %init %entry %next %latch\n%sum = OpPhi %v3float %zero3 %entry %sum2 %latch\n\
    %cond = OpULessThan %bool %i %u4\nOpLoopMerge %exit %latch None\nOpBranchConditional %cond %body %exit\n\
    %body = OpLabel\nTRACE%p = OpLoad %v3float %payload\n%sum2 = OpFAdd %v3float %sum %p\n%next = OpIAdd %uint %i %u1\nOpBranch %latch\n\
    %latch = OpLabel\nOpBranch %header\n\
    %exit = OpLabel\n%picked = OpPhi %float %exit_only %header\n%scaled = OpVectorTimesScalar %v3float %sum %k\n\
    %out = OpVectorTimesScalar %v3float %scaled %picked\nOpStore %payload %out\nOpReturn\nOpFunctionEnd\n";

#[test]
fn values_carried_around_a_loop_are_live_across_a_trace_in_it() {
    let sites = sites(&LOOP.replace("TRACE", &trace("dir")));
    assert_eq!(sites.len(), 1);
    let s = &sites[0];
    // The counter and the sum (the header's phis), %k (used after the loop), %exit_only (a phi
    // operand on the header's exit edge) and the direction (traced again next iteration). Not
    // %init, which only enters the loop, nor the trace's handle.
    assert_eq!(live_ids(s), ["OpCompositeConstruct:12", "OpFAdd:4", "OpFMul:4", "OpPhi:12", "OpPhi:4"]);
    assert_eq!(s.bytes, 12 + 4 + 4 + 12 + 4);
    assert_eq!(s.loops.len(), 1);
    assert_eq!((s.loops[0].carried, s.loops[0].carried_bytes), (2, 16));
}

#[test]
fn a_return_behind_a_constant_false_branch_is_dropped_before_it_can_become_a_carried_flag() {
    // What rust-gpu leaves of core's `if false { panic }` precondition checks: a return on a
    // branch no driver keeps. Left in, merge-return would turn it into a flag carried by the
    // loop and live across the trace.
    let bail = "OpSelectionMerge %cont None\nOpBranchConditional %false %bail %cont\n\
                %bail = OpLabel\nOpReturn\n%cont = OpLabel\n";
    // Two loops, so that the flag would go round the outer one through the inner one's exit.
    let nested = format!(
        "%main = OpFunction %void None %fn\n%entry = OpLabel\n%seed = OpLoad %float %seedvar\n\
         %dir = OpCompositeConstruct %v3float %seed %f0 %f0\nOpBranch %oh\n\
         %oh = OpLabel\n%o = OpPhi %uint %u0 %entry %onext %olatch\n%ocond = OpULessThan %bool %o %u4\n\
         OpLoopMerge %oexit %olatch None\nOpBranchConditional %ocond %obody %oexit\n\
         %obody = OpLabel\nOpBranch %header\n\
         %header = OpLabel\n%i = OpPhi %uint %u0 %obody %next %latch\n%cond = OpULessThan %bool %i %u4\n\
         OpLoopMerge %iexit %latch None\nOpBranchConditional %cond %body %iexit\n\
         %body = OpLabel\n{}BAIL%next = OpIAdd %uint %i %u1\nOpBranch %latch\n\
         %latch = OpLabel\nOpBranch %header\n\
         %iexit = OpLabel\n%onext = OpIAdd %uint %o %u1\nOpBranch %olatch\n\
         %olatch = OpLabel\nOpBranch %oh\n\
         %oexit = OpLabel\nOpReturn\nOpFunctionEnd\n\
         %shade = OpFunction %float None %fn_shade\n%arg = OpFunctionParameter %ptr_float\n\
         %start = OpLabel\n%kept = OpLoad %float %arg\nOpReturnValue %kept\nOpFunctionEnd\n",
        trace("dir")
    );
    let looped = nested.replace("BAIL", "");
    let body = nested.replace("BAIL", bail);
    let plain = inspect(&normalise(&assemble(&looped), &[]).unwrap()).unwrap();
    let normal = inspect(&normalise(&assemble(&body), &[]).unwrap()).unwrap();
    let site = &normal[0].sites[0];
    assert!(site.live.iter().all(|l| l.ty != "bool"), "{:?}", live_ids(site));
    assert_eq!(site.bytes, plain[0].sites[0].bytes);
}

#[test]
fn a_trace_in_a_called_function_keeps_what_its_callers_keep_across_the_call() {
    // main keeps %x across its call to shade and reads its variable %kept after; shade keeps
    // %y across its trace and reads %kept (through its parameter) after it: one variable, so
    // counted once.
    let body = format!(
        "%main = OpFunction %void None %fn\n%entry = OpLabel\n%kept = OpVariable %ptr_float Function\n\
         OpStore %kept %f1\n%seed = OpLoad %float %seedvar\n%x = OpFAdd %float %seed %f1\n\
         %r = OpFunctionCall %float %shade %kept\n%back = OpLoad %float %kept\n\
         %sum = OpFAdd %float %r %x\n%total = OpFAdd %float %sum %back\n\
         %v = OpCompositeConstruct %v3float %total %total %total\nOpStore %payload %v\nOpReturn\nOpFunctionEnd\n\
         %shade = OpFunction %float None %fn_shade\n%param = OpFunctionParameter %ptr_float\n%sentry = OpLabel\n\
         %sseed = OpLoad %float %seedvar\n%y = OpFMul %float %sseed %f1\n%dir = OpCompositeConstruct %v3float %f1 %f0 %f0\n{}\
         %read = OpLoad %float %param\n%ret = OpFAdd %float %read %y\nOpReturnValue %ret\nOpFunctionEnd\n",
        trace("dir")
    );
    let sites = sites(&body);
    assert_eq!(sites.len(), 1);
    let s = &sites[0];
    assert_eq!(s.path, ["main", "shade"]);
    assert_eq!(live_ids(s), ["OpFAdd:4", "OpFMul:4", "OpVariable:4"]);
    let variable = s.live.iter().find(|l| l.kind == "variable").unwrap();
    assert_eq!((variable.function.as_str(), variable.origin.as_deref()), ("main", Some("\"kept\"")));
}

#[test]
fn a_variable_written_whole_after_the_call_is_not_live_across_it_but_one_written_in_part_is() {
    let body = |store: &str| {
        format!(
            "%main = OpFunction %void None %fn\n%entry = OpLabel\n%var = OpVariable %ptr_vec2 Function\n\
             %two = OpCompositeConstruct %v2float %f1 %f1\nOpStore %var %two\n\
             %dir = OpCompositeConstruct %v3float %f1 %f0 %f0\n{}{store}\
             %got = OpLoad %v2float %var\n%x = OpCompositeExtract %float %got 0\n\
             %v = OpCompositeConstruct %v3float %x %x %x\nOpStore %payload %v\nOpReturn\nOpFunctionEnd\n",
            trace("dir")
        )
    };
    let whole = sites(&body("%new = OpCompositeConstruct %v2float %f0 %f0\nOpStore %var %new\n"));
    assert!(whole[0].live.is_empty(), "{:?}", whole[0].live);
    let part = sites(&body("%first = OpAccessChain %ptr_float %var %u0\nOpStore %first %f0\n"));
    assert_eq!(live_ids(&part[0]), ["OpVariable:8"]);
}

#[test]
fn glslang_debug_lines_name_where_each_value_comes_from() {
    let source = "#version 460\n#extension GL_EXT_ray_tracing : require\n\
        layout(set = 0, binding = 0) uniform accelerationStructureEXT tlas;\n\
        layout(location = 0) rayPayloadEXT vec3 payload;\n\
        void main() {\n  vec3 sum = vec3(0.0);\n  float kept = float(gl_LaunchIDEXT.x) * 0.5;\n\
          for (int i = 0; i < 4; i++) {\n    traceRayEXT(tlas, 0u, 255u, 0u, 0u, 0u, vec3(0.0), 0.0, vec3(1.0, 0.0, 0.0), 10.0, 0);\n\
            sum += payload * kept;\n  }\n  payload = sum;\n}\n";
    let dir = std::env::temp_dir().join(format!("twinray-inspect-glsl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (src, out) = (dir.join("stage.rgen"), dir.join("stage.spv"));
    std::fs::write(&src, source).unwrap();
    let run = Command::new("glslangValidator")
        .args(["-V", "-g", "--target-env", "spirv1.4", "-o"])
        .arg(&out)
        .arg(&src)
        .output()
        .expect("glslangValidator runs (cargo xtask setup installs it)");
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stdout));
    let bytes = std::fs::read(&out).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    // As written: glslang keeps every local in a variable; sum, kept and i are live across
    // the trace, each with its line.
    let raw = inspect(&bytes).unwrap();
    let site = &raw[0].sites[0];
    let named: Vec<&str> = site.live.iter().filter_map(|l| l.origin.as_deref()).collect();
    for (line, name) in [(6, "sum"), (7, "kept"), (8, "i")] {
        let want = format!("stage.rgen:{line} ({name})");
        assert!(named.iter().any(|o| o.ends_with(&want)), "{want} in {named:?}");
    }
    assert_eq!(site.bytes, 12 + 4 + 4);
    // Normalised, the same three are SSA values: the same bytes.
    let normal = inspect(&normalise(&bytes, &[]).unwrap()).unwrap();
    assert_eq!(normal[0].sites[0].bytes, 12 + 4 + 4);
    assert_eq!(normal[0].sites[0].loops.len(), 1);
}

#[test]
fn hostile_bytes_are_refused_in_words() {
    assert!(inspect(&[1, 2, 3]).unwrap_err().contains("not a SPIR-V module"));
    assert!(inspect(&[0u8; 64]).is_err());
}
