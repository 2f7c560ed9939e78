// SPDX-License-Identifier: BSD-3-Clause
// Test driver (issue 19): writes a .ksplat with GaussianSplats3D's own PLY parser and
// SplatBuffer generator (installed by install-gaussian-splats-3d.sh), the way its
// util/create-ksplat.js does. Usage:
//   node make-ksplat.mjs IN.ply OUT.ksplat LEVEL SH_DEGREE [BLOCK_SIZE=5] [BUCKET_SIZE=256]
import * as fs from 'fs';
import * as GS3D from '@mkkellogg/gaussian-splats-3d';

const [input, output, level, shDegree, blockSize = '5', bucketSize = '256'] = process.argv.slice(2);
const bytes = fs.readFileSync(input);
const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const splats = GS3D.PlyParser.parseToUncompressedSplatArray(buffer, parseInt(shDegree));
// Alpha removal threshold 1 (the tool's default), one section, scene centre at the origin.
const generator = GS3D.SplatBufferGenerator.getStandardGenerator(
  1, parseInt(level), 0, undefined, parseFloat(blockSize), parseInt(bucketSize));
const splatBuffer = generator.generateFromUncompressedSplatArray(splats);
fs.writeFileSync(output, Buffer.from(splatBuffer.bufferData));
